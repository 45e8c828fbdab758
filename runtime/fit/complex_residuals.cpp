#include "runtime/fit/complex_residuals.hpp"
#include "runtime/fit/objective.hpp"

#include <cmath>
#include <stdexcept>

namespace rheo::runtime {

ComplexResiduals::ComplexResiduals(const FitDataSet& set, const ScoreSettings& score) : phi_(score.objective == FitObjective::phi) {
  if (!set.is_harmonic()) throw std::logic_error("complex residuals need a harmonic data set");
  const HarmonicData& d = set.harmonic();
  points_.resize(d.size());
  for (std::size_t i = 0; i < d.size(); ++i) {
    Point& p = points_[i];
    const double point_scale = harmonic_point_scale(set, i);
    const double phase = d.phase[i];
    if (phi_) {
      p.stiffness_scale = point_scale * std::sqrt(score.stiffness_weight);
      const bool damped = keeps_damping_term(phase);
      p.damping_scale = damped ? point_scale * std::sqrt(score.damping_weight) : 0.0;
      p.signed_measured = signed_stiffness(d.stiffness[i], phase);
      p.measured_sine = damped ? std::sin(phase) : 1.0;
    } else {
      p.stiffness_scale = p.damping_scale = point_scale;
      p.measured = std::polar(d.stiffness[i], phase);
      p.measured_stiffness = d.stiffness[i];
    }
  }
}

double ComplexResiduals::terms(const std::vector<std::complex<double>>& model, double shift, std::vector<double>& out) const {
  if (model.size() != points_.size()) throw std::logic_error("complex residuals: one model stiffness per data point");
  out.resize(2 * points_.size());
  double sum = 0.0;
  for (std::size_t j = 0; j < points_.size(); ++j) {
    const Point& p = points_[j];
    const std::complex<double> k = model[j] + shift;
    double stiffness_term, damping_term;
    if (phi_) {
      const double magnitude = std::abs(k), sine = magnitude > 0.0 ? k.imag() / magnitude : 0.0;  // sin(arg 0) = 0
      stiffness_term = p.stiffness_scale * ((k.real() < 0.0 ? -magnitude : magnitude) / p.signed_measured - 1.0);
      damping_term = p.damping_scale == 0.0 ? 0.0 : p.damping_scale * (sine / p.measured_sine - 1.0);
    } else {
      const std::complex<double> r = (k - p.measured) / p.measured_stiffness;
      stiffness_term = p.stiffness_scale * r.real();
      damping_term = p.damping_scale * r.imag();
    }
    out[2 * j] = stiffness_term, out[2 * j + 1] = damping_term;
    sum += stiffness_term * stiffness_term;
    sum += damping_term * damping_term;  // in append_residuals' order, term by term
  }
  return sum;
}

}  // namespace rheo::runtime
