#include "runtime/fit/harmonic_jacobian.hpp"

#include "runtime/closed_form/closed_form_sensitivity.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/core/parallel_for.hpp"
#include "runtime/fit/objective.hpp"
#include "runtime/protocols/harmonic.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>

namespace rheo::runtime {
namespace {

// dC/dz (coefficients x free parameters) by central differences of the compiled coefficients,
// the columns side by side on THREADS; nothing where a moved value is refused (a springpot's
// band). COEFFICIENTS: the count of coefficient_vector at z.
std::optional<Eigen::MatrixXd> coefficient_jacobian(const Coordinates& coordinates, const std::vector<double>& z, std::size_t coefficients,
                                                    int threads) {
  const std::size_t n = z.size();
  Eigen::MatrixXd out = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(coefficients), static_cast<Eigen::Index>(n));
  try {
    parallel_for(n, threads, [&](std::size_t j) {
      std::vector<double> moved = z;
      const double h = 1e-4 * std::max(std::abs(z[j]), 1.0);
      moved[j] = z[j] + h;
      const std::vector<double> up = coefficient_vector(coordinates.network(moved).coefficients());
      moved[j] = z[j] - h;
      const std::vector<double> down = coefficient_vector(coordinates.network(moved).coefficients());
      if (up.size() != coefficients || down.size() != coefficients) throw std::logic_error("coefficient_jacobian: the coefficient count moved");
      for (std::size_t k = 0; k < coefficients; ++k)
        out(static_cast<Eigen::Index>(k), static_cast<Eigen::Index>(j)) = (up[k] - down[k]) / (2.0 * h);
    });
  } catch (const UserError&) {
    return std::nullopt;
  }
  return out;
}

// Writes the two rows of point I of one harmonic file's residual terms (as append_residuals
// orders them) at ROW and ROW + 1.
void point_rows(const FitDataSet& set, std::size_t i, const HarmonicSensitivity& s, const Eigen::MatrixXd& dc_dz, const ScoreSettings& settings,
                Eigen::MatrixXd& jacobian, Eigen::Index row) {
  const HarmonicData& d = set.harmonic();
  const HarmonicDefinition definition = settings.harmonic.definition;
  const auto n = dc_dz.cols();
  const Eigen::Map<const Eigen::VectorXd> f(s.force_amplitude.data(), dc_dz.rows()), k1(s.storage.data(), dc_dz.rows()),
      k2(s.loss.data(), dc_dz.rows());
  const Eigen::VectorXd df = dc_dz.transpose() * f, dk1 = dc_dz.transpose() * k1, dk2 = dc_dz.transpose() * k2;
  const CycleMeasures& m = s.point.measures;
  const double g = harmonic_point_scale(set, i);
  const double measured_k = d.stiffness[i], measured_phase = d.phase[i];
  for (Eigen::Index j = 0; j < n; ++j) {
    const MeasureDerivative dm = measure_derivative(s, definition, df(j), dk1(j), dk2(j));
    if (settings.objective == FitObjective::phi) {
      // d(stiffness_residual): both stiffnesses signed as eq. 5.1's term signs them (the sign is
      // constant between resonances, so the model's derivative takes the model's sign).
      jacobian(row, j) = g * std::sqrt(settings.stiffness_weight) * signed_stiffness(dm.stiffness, m.phase) /
                         signed_stiffness(measured_k, measured_phase);
      jacobian(row + 1, j) = keeps_damping_term(measured_phase) ? g * std::sqrt(settings.damping_weight) * dm.sine / std::sin(measured_phase) : 0.0;
    } else {
      const double sine = std::sin(m.phase), cosine = std::cos(m.phase);
      jacobian(row, j) = g * (dm.stiffness * cosine + m.stiffness * dm.cosine) / measured_k;
      jacobian(row + 1, j) = g * (dm.stiffness * sine + m.stiffness * dm.sine) / measured_k;
    }
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
  const int threads = score.harmonic.threads;
  const std::optional<Eigen::MatrixXd> dc_dz = coefficient_jacobian(coordinates, z, coefficient_vector(network.coefficients()).size(), threads);
  ResidualsWithJacobian out;
  std::size_t rows = 0;
  for (const FitDataSet& set : data) rows += 2 * set.harmonic().size();
  if (dc_dz) out.jacobian = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(rows), static_cast<Eigen::Index>(z.size()));
  Eigen::Index first_row = 0;
  std::vector<HarmonicSensitivity> points;
  for (const FitDataSet& set : data) {
    const HarmonicData& d = set.harmonic();
    points.assign(d.size(), {});
    // Each point's sensitivities and its two rows, side by side: the rows of point i are
    // first_row + 2i and + 2i + 1, written by its item alone.
    parallel_for(d.size(), threads, [&](std::size_t i) {
      points[i] = harmonic_sensitivity(network, d.amplitude[i], d.frequency[i], score.harmonic.definition);
      if (dc_dz) point_rows(set, i, points[i], *dc_dz, score, out.jacobian, first_row + 2 * static_cast<Eigen::Index>(i));
    });
    Prediction prediction;
    for (const HarmonicSensitivity& s : points) prediction.points.push_back(s.point);
    append_residuals(set, prediction, score, out.residuals);
    first_row += 2 * static_cast<Eigen::Index>(d.size());
  }
  return out;
}

}  // namespace rheo::runtime
