#include "runtime/fit/objective.hpp"
#include "runtime/protocols/harmonic.hpp"

#include "runtime/core/parallel_for.hpp"

#include <fmt/format.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace rheo::runtime {

double damping_residual(double model_phase, double measured_phase) {
  return keeps_damping_term(measured_phase) ? std::sin(model_phase) / std::sin(measured_phase) - 1.0 : 0.0;
}

double stiffness_residual(double model_stiffness, double model_phase, double measured_stiffness, double measured_phase) {
  return signed_stiffness(model_stiffness, model_phase) / signed_stiffness(measured_stiffness, measured_phase) - 1.0;
}

std::vector<std::string> damping_left_out(const HarmonicData& data) {
  std::vector<std::string> notes;
  for (std::size_t i = 0; i < data.size(); ++i)
    if (!(data.phase[i] > 0.0))
      notes.push_back(
          fmt::format("{}:{}: phase {:g} deg <= 0 (noise on a nearly elastic point): its damping term is left out of "
                      "eq. 5.1, which divides by sin(phase)",
                      data.path, data.rows[i], data.phase[i] * 180.0 / std::numbers::pi));
    else if (!(data.phase[i] < std::numbers::pi))
      notes.push_back(
          fmt::format("{}:{}: phase {:g} deg >= 180 (noise on a nearly undamped mass-dominated point): its damping term is left "
                      "out of eq. 5.1, which divides by sin(phase)",
                      data.path, data.rows[i], data.phase[i] * 180.0 / std::numbers::pi));
  return notes;
}

RelativeResiduals relative_residuals(const HarmonicData& data, const std::vector<HarmonicPoint>& model) {
  if (model.size() != data.size()) throw std::logic_error("model and data have different numbers of points");
  RelativeResiduals r;
  for (std::size_t i = 0; i < data.size(); ++i) {
    r.stiffness.push_back(stiffness_residual(model[i].measures.stiffness, model[i].measures.phase, data.stiffness[i], data.phase[i]));
    r.damping.push_back(damping_residual(model[i].measures.phase, data.phase[i]));
  }
  return r;
}

double phi(const RelativeResiduals& r, double stiffness_weight, double damping_weight) {
  double sum = 0.0;
  for (std::size_t i = 0; i < r.stiffness.size(); ++i)
    sum += stiffness_weight * r.stiffness[i] * r.stiffness[i] + damping_weight * r.damping[i] * r.damping[i];
  return sum;
}

double thesis_err(const RelativeResiduals& r) { return std::sqrt(phi(r, 1.0, 1.0)) / static_cast<double>(r.stiffness.size()); }

std::vector<HarmonicPoint> simulate_at(const Network& network, const HarmonicData& data, const HarmonicOptions& options) {
  std::vector<HarmonicPoint> points(data.size());
  parallel_for(data.size(), options.threads, [&](std::size_t i) {
    points[i] = simulate_harmonic_point(network, data.amplitude[i], data.frequency[i], options, data.preload.empty() ? 0.0 : data.preload[i]);
  });
  return points;
}

}  // namespace rheo::runtime
