#include "runtime/fit/harmonic_jacobian.hpp"

#include "runtime/closed_form/closed_form_sensitivity.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/core/parallel_for.hpp"
#include "runtime/protocols/harmonic.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <optional>

namespace rheo::runtime {
namespace {

// dC/dz (coefficients x free parameters) by central differences of the compiled coefficients;
// nothing where a moved value is refused (a springpot's band).
std::optional<Eigen::MatrixXd> coefficient_jacobian(const Coordinates& coordinates, const std::vector<double>& z) {
  const std::size_t n = z.size();
  std::optional<Eigen::MatrixXd> out;
  std::vector<double> moved = z;
  try {
    for (std::size_t j = 0; j < n; ++j) {
      const double h = 1e-4 * std::max(std::abs(z[j]), 1.0);
      moved[j] = z[j] + h;
      const std::vector<double> up = coefficient_vector(coordinates.network(moved).coefficients());
      moved[j] = z[j] - h;
      const std::vector<double> down = coefficient_vector(coordinates.network(moved).coefficients());
      moved[j] = z[j];
      if (!out) out = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(up.size()), static_cast<Eigen::Index>(n));
      for (std::size_t k = 0; k < up.size(); ++k)
        (*out)(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) = (up[k] - down[k]) / (2.0 * h);
    }
  } catch (const UserError&) {
    return std::nullopt;
  }
  return out;
}

// Appends the rows of one harmonic file's residual terms (as append_residuals orders them).
void append_rows(const FitDataSet& set, const std::vector<HarmonicSensitivity>& points, const Eigen::MatrixXd& dc_dz, const ScoreSettings& settings,
                 Eigen::MatrixXd& jacobian, Eigen::Index& row) {
  const HarmonicData& d = set.harmonic();
  const HarmonicDefinition definition = settings.harmonic.definition;
  const double scale = std::sqrt(set.weight / (2.0 * static_cast<double>(d.size())));
  const auto n = dc_dz.cols();
  for (std::size_t i = 0; i < d.size(); ++i) {
    const HarmonicSensitivity& s = points[i];
    const Eigen::Map<const Eigen::VectorXd> f(s.force_amplitude.data(), dc_dz.rows()), k1(s.storage.data(), dc_dz.rows()),
        k2(s.loss.data(), dc_dz.rows());
    const Eigen::VectorXd df = dc_dz.transpose() * f, dk1 = dc_dz.transpose() * k1, dk2 = dc_dz.transpose() * k2;
    const CycleMeasures& m = s.point.measures;
    const double g = d.weight.empty() ? scale : scale * std::sqrt(d.weight[i]);
    const double measured_k = d.stiffness[i], measured_phase = d.phase[i];
    for (Eigen::Index j = 0; j < n; ++j) {
      const MeasureDerivative dm = measure_derivative(s, definition, df(j), dk1(j), dk2(j));
      if (settings.objective == FitObjective::phi) {
        const double model_sign = std::cos(m.phase) < 0.0 ? -1.0 : 1.0, measured_sign = std::cos(measured_phase) < 0.0 ? -1.0 : 1.0;
        jacobian(row, j) = g * std::sqrt(settings.stiffness_weight) * model_sign * dm.stiffness / (measured_sign * measured_k);
        const bool damping_term = measured_phase > 0.0 && measured_phase < std::numbers::pi;
        jacobian(row + 1, j) = damping_term ? g * std::sqrt(settings.damping_weight) * dm.sine / std::sin(measured_phase) : 0.0;
      } else {
        const double sine = std::sin(m.phase), cosine = std::cos(m.phase);
        jacobian(row, j) = g * (dm.stiffness * cosine + m.stiffness * dm.cosine) / measured_k;
        jacobian(row + 1, j) = g * (dm.stiffness * sine + m.stiffness * dm.sine) / measured_k;
      }
    }
    row += 2;
  }
}

}  // namespace

bool residual_jacobian_applies(const Network& network, const std::vector<FitDataSet>& data, const ScoreSettings& score, FitMethod method) {
  if (method != FitMethod::exact || !has_coefficient_sensitivities(network) || !uses_closed_form(network, score.harmonic)) return false;
  return std::all_of(data.begin(), data.end(), [](const FitDataSet& set) {
    return set.is_harmonic() && std::all_of(set.harmonic().preload.begin(), set.harmonic().preload.end(), [](double p) { return p == 0.0; });
  });
}

ResidualsWithJacobian residual_jacobian(const Coordinates& coordinates, const std::vector<double>& z, const std::vector<FitDataSet>& data,
                                        const ScoreSettings& score) {
  const Network network = coordinates.network(z);
  const std::optional<Eigen::MatrixXd> dc_dz = coefficient_jacobian(coordinates, z);
  ResidualsWithJacobian out;
  std::size_t rows = 0;
  for (const FitDataSet& set : data) rows += 2 * set.harmonic().size();
  if (dc_dz) out.jacobian = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(z.size()));
  Eigen::Index row = 0;
  std::vector<HarmonicSensitivity> points;
  for (const FitDataSet& set : data) {
    const HarmonicData& d = set.harmonic();
    points.assign(d.size(), {});
    parallel_for(d.size(), score.harmonic.threads,
                 [&](std::size_t i) { points[i] = harmonic_sensitivity(network, d.amplitude[i], d.frequency[i], score.harmonic.definition); });
    Prediction prediction;
    for (const HarmonicSensitivity& s : points) prediction.points.push_back(s.point);
    append_residuals(set, prediction, score, out.residuals);
    if (dc_dz) append_rows(set, points, *dc_dz, score, out.jacobian, row);
  }
  return out;
}

}  // namespace rheo::runtime
