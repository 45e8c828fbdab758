#include "runtime/core/cycle_measures.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <vector>

namespace cycle_measures_test {

using namespace rheo::runtime;

TEST_CASE("an ellipse: F^ = K u0, U = pi F^ u0 sin(delta), both definitions agree") {
  const int n = 256;
  // delta a whole number of sample spacings, so that the force peaks fall on samples.
  const double u0 = 0.7, stiffness = 300, delta = 2 * std::numbers::pi * 12 / n;
  std::vector<double> phase(n), u(n), f(n);
  for (std::size_t k = 0; k < phase.size(); ++k) {
    phase[k] = 2 * std::numbers::pi * static_cast<double>(k) / n;
    u[k] = u0 * std::sin(phase[k]);
    f[k] = stiffness * u0 * std::sin(phase[k] + delta);
  }
  const CycleSamples s{phase, u, f};
  const double energy = std::numbers::pi * stiffness * u0 * u0 * std::sin(delta);
  CHECK(loop_energy(s) == doctest::Approx(energy).epsilon(2e-4));  // trapezoid: second order
  for (auto def : {HarmonicDefinition::thesis, HarmonicDefinition::first_harmonic}) {
    const auto m = measure_cycle(s, u0, def);
    CHECK(m.energy == doctest::Approx(energy).epsilon(1e-12));  // Fourier identity: exact
    CHECK(m.stiffness == doctest::Approx(stiffness).epsilon(1e-9));
    CHECK(m.phase == doctest::Approx(delta).epsilon(1e-9).scale(0.0));
    CHECK(m.storage == doctest::Approx(stiffness * std::cos(delta)).epsilon(1e-9));
    CHECK(m.loss == doctest::Approx(stiffness * std::sin(delta)).epsilon(1e-9));
  }
}

TEST_CASE("a rigid-plastic slider's square loop has d = 4/pi: clamped to 90 deg and flagged") {
  const int n = 64;
  std::vector<double> phase(n), u(n), f(n);
  for (std::size_t k = 0; k < phase.size(); ++k) {
    phase[k] = 2 * std::numbers::pi * (static_cast<double>(k) + 0.5) / n;
    u[k] = std::sin(phase[k]);
    f[k] = std::cos(phase[k]) > 0 ? 1.0 : -1.0;
  }
  const auto m = measure_cycle({phase, u, f}, 1.0, HarmonicDefinition::thesis);
  CHECK(m.damping_clamped);
  CHECK(m.phase == doctest::Approx(std::numbers::pi / 2));
}

TEST_CASE("above a resonance (K'_1 < 0) the thesis phase lies beyond 90 deg, as the first harmonic's") {
  // An ellipse lagging by delta in (90, 180) deg: F = K u0 sin(theta + delta). Both definitions
  // give K and delta; before, the thesis definition folded the phase to 180 - delta.
  const double u0 = 0.4, stiffness = 50.0;
  for (double degrees : {95.0, 135.0, 179.0}) {
    const double delta = degrees * std::numbers::pi / 180.0;
    const double storage = stiffness * std::cos(delta), loss = stiffness * std::sin(delta);
    const CycleMeasures thesis = measures_from(stiffness * u0, storage, loss, u0, HarmonicDefinition::thesis);
    const CycleMeasures first = measures_from(stiffness * u0, storage, loss, u0, HarmonicDefinition::first_harmonic);
    CAPTURE(degrees);
    CHECK(thesis.phase == doctest::Approx(delta).epsilon(1e-12));
    CHECK(first.phase == doctest::Approx(delta).epsilon(1e-12));
    CHECK(thesis.damping == doctest::Approx(std::sin(delta)).epsilon(1e-12).scale(0.0));  // d = U/(pi F^ u0) unchanged
    CHECK(thesis.storage == doctest::Approx(storage).epsilon(1e-12));                     // negative: the sign is kept
  }
  // A pure mass: no loss, K'_1 < 0: 180 deg, not 0.
  CHECK(measures_from(2.0, -5.0, 0.0, 0.4, HarmonicDefinition::thesis).phase == doctest::Approx(std::numbers::pi));
  CHECK(measures_from(2.0, 5.0, 0.0, 0.4, HarmonicDefinition::thesis).phase == doctest::Approx(0.0));
}

}  // namespace cycle_measures_test
