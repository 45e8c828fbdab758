#include "runtime/core/cycle_measures.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace rheo::runtime {

double loop_energy(const CycleSamples& s) {
  const std::size_t n = s.force.size();
  double energy = 0.0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t next = (k + 1) % n;
    energy += 0.5 * (s.force[k] + s.force[next]) * (s.displacement[next] - s.displacement[k]);
  }
  return energy;
}

CycleMeasures measures_from(double force_amplitude, double storage1, double loss1, double amplitude, HarmonicDefinition definition) {
  CycleMeasures m;
  m.force_amplitude = force_amplitude;
  // With du = u0 w cos(w t) dt the loop integral is exactly pi u0^2 K''_1 for any periodic F.
  m.energy = std::numbers::pi * amplitude * amplitude * loss1;
  if (definition == HarmonicDefinition::thesis) {
    m.stiffness = m.force_amplitude / amplitude;
    m.damping = m.force_amplitude > 0.0 ? m.energy / (std::numbers::pi * m.force_amplitude * amplitude) : 0.0;
    m.damping_clamped = m.damping > 1.0;
    m.phase = std::asin(std::clamp(m.damping, -1.0, 1.0));
    // Where the in-phase part of the force opposes the displacement (K'_1 < 0, a mass above its
    // resonance) the phase lies beyond 90 deg, as the first harmonic's does: d = sin(phase) and
    // F^/u0 keep their values, the sign of K' is kept in the phase (#22 item 8).
    if (storage1 < 0.0) m.phase = std::numbers::pi - m.phase;
  } else {
    m.stiffness = std::hypot(storage1, loss1);
    m.phase = std::atan2(loss1, storage1);
    m.damping = std::sin(m.phase);
  }
  m.storage = m.stiffness * std::cos(m.phase);
  m.loss = m.stiffness * std::sin(m.phase);
  return m;
}

CycleMeasures measure_cycle(const CycleSamples& s, double amplitude, HarmonicDefinition definition) {
  const auto [lo, hi] = std::minmax_element(s.force.begin(), s.force.end());
  double in_phase = 0.0, quadrature = 0.0;
  const std::size_t n = s.force.size();
  for (std::size_t k = 0; k < n; ++k) {
    in_phase += s.force[k] * std::sin(s.phase[k]);
    quadrature += s.force[k] * std::cos(s.phase[k]);
  }
  const double scale = 2.0 / (static_cast<double>(n) * amplitude);
  return measures_from(0.5 * (*hi - *lo), in_phase * scale, quadrature * scale, amplitude, definition);
}

}  // namespace rheo::runtime
