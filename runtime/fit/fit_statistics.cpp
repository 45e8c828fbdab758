#include "runtime/fit/fit_statistics.hpp"

#include "runtime/core/errors.hpp"

#include <Eigen/Dense>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace rheo::runtime {
namespace {

constexpr double kSingularTolerance = 1e-8;  // of the largest singular value
constexpr double kNullComponent = 1e-6;
constexpr double kUndeterminedRelativeError = 1e3;  // standard error over |value| beyond which a parameter is not identifiable
constexpr double kGroupComponent = 0.1;             // of a singular vector, for the groups that act together

Eigen::VectorXd evaluate(const std::function<std::vector<double>(const std::vector<double>&)>& residuals, const std::vector<double>& z,
                         std::size_t expected_size) {
  const std::vector<double> r = residuals(z);
  if (expected_size != 0 && r.size() != expected_size)
    throw std::logic_error(fmt::format("parameter_statistics: the residual vector changed size ({} -> {})", expected_size, r.size()));
  for (double v : r)
    if (!std::isfinite(v)) throw NumericalError(kStatisticsNotFinite);
  return Eigen::Map<const Eigen::VectorXd>(r.data(), static_cast<Eigen::Index>(r.size()));
}

// The undetermined subspace U: J's null directions, and each direction along which alone some
// coordinate's standard error exceeds the practical bound (kUndeterminedRelativeError times its
// value; `variance_scale` s^2, `bound` per coordinate in z units). P = V_U V_U^T is its projector
// (independent of the basis chosen inside U). Non-identifiable coordinates i, j act together when
// |P_ij| > kGroupComponent^2; each connected group C holds round(sum_{i in C} P_ii) undetermined
// directions, so the data fix |C| minus that many combinations of its parameters.
void group_undetermined(const Eigen::MatrixXd& v, const Eigen::VectorXd& inverse_square, double variance_scale, const std::vector<double>& bound,
                        ParameterStatistics& out) {
  const Eigen::Index n = v.rows();
  std::vector<bool> in_u(static_cast<std::size_t>(n), false);
  for (Eigen::Index k = 0; k < n; ++k) {
    in_u[static_cast<std::size_t>(k)] = inverse_square(k) == 0.0;
    for (Eigen::Index j = 0; j < n; ++j)
      if (!out.identifiable[static_cast<std::size_t>(j)] &&
          variance_scale * v(j, k) * v(j, k) * inverse_square(k) > bound[static_cast<std::size_t>(j)] * bound[static_cast<std::size_t>(j)])
        in_u[static_cast<std::size_t>(k)] = true;
  }
  Eigen::MatrixXd projector = Eigen::MatrixXd::Zero(n, n);
  for (Eigen::Index k = 0; k < n; ++k)
    if (in_u[static_cast<std::size_t>(k)]) projector += v.col(k) * v.col(k).transpose();
  std::vector<int> component(static_cast<std::size_t>(n), -1);
  int components = 0;
  for (Eigen::Index seed = 0; seed < n; ++seed) {
    if (out.identifiable[static_cast<std::size_t>(seed)] || component[static_cast<std::size_t>(seed)] >= 0) continue;
    std::vector<Eigen::Index> stack{seed};
    component[static_cast<std::size_t>(seed)] = components;
    while (!stack.empty()) {
      const Eigen::Index i = stack.back();
      stack.pop_back();
      for (Eigen::Index j = 0; j < n; ++j)
        if (!out.identifiable[static_cast<std::size_t>(j)] && component[static_cast<std::size_t>(j)] < 0 &&
            std::abs(projector(i, j)) > kGroupComponent * kGroupComponent)
          component[static_cast<std::size_t>(j)] = components, stack.push_back(j);
    }
    ++components;
  }
  for (int c = 0; c < components; ++c) {
    std::vector<int> group;
    double trace = 0.0;
    for (Eigen::Index j = 0; j < n; ++j)
      if (component[static_cast<std::size_t>(j)] == c) group.push_back(static_cast<int>(j)), trace += projector(j, j);
    if (group.size() < 2) continue;
    out.together.push_back(group);
    out.undetermined.push_back(std::clamp(static_cast<int>(std::lround(trace)), 1, static_cast<int>(group.size())));
  }
}

}  // namespace

ParameterStatistics parameter_statistics(const std::function<std::vector<double>(const std::vector<double>&)>& residuals,
                                         const std::vector<double>& z, const std::vector<bool>& logarithmic) {
  const std::size_t n = z.size();
  if (n == 0 || logarithmic.size() != n)
    throw std::logic_error(fmt::format("parameter_statistics: {} coordinates and {} log flags", n, logarithmic.size()));
  const Eigen::VectorXd r0 = evaluate(residuals, z, 0);
  const std::size_t m = static_cast<std::size_t>(r0.size());
  if (m == 0) throw std::logic_error("parameter_statistics: empty residual vector");

  Eigen::MatrixXd jacobian(static_cast<Eigen::Index>(m), static_cast<Eigen::Index>(n));
  std::vector<double> shifted = z;
  for (std::size_t j = 0; j < n; ++j) {
    const double h = kStatisticsRelativeStep * std::max(1.0, std::abs(z[j]));
    shifted[j] = z[j] + h;
    const double up = shifted[j];
    const Eigen::VectorXd r_up = evaluate(residuals, shifted, m);
    shifted[j] = z[j] - h;
    const double down = shifted[j];
    const Eigen::VectorXd r_down = evaluate(residuals, shifted, m);
    shifted[j] = z[j];
    jacobian.col(static_cast<Eigen::Index>(j)) = (r_up - r_down) / (up - down);
  }
  return parameter_statistics(r0, jacobian, z, logarithmic);
}

ParameterStatistics parameter_statistics(const Eigen::VectorXd& r0, const Eigen::MatrixXd& jacobian, const std::vector<double>& z,
                                         const std::vector<bool>& logarithmic) {
  const std::size_t n = z.size(), m = static_cast<std::size_t>(r0.size());
  if (n == 0 || logarithmic.size() != n || jacobian.rows() != r0.size() || jacobian.cols() != static_cast<Eigen::Index>(n) || m == 0)
    throw std::logic_error(fmt::format("parameter_statistics: {} coordinates, {} log flags, {} residuals and a {} x {} Jacobian", n,
                                       logarithmic.size(), m, jacobian.rows(), jacobian.cols()));
  if (!r0.allFinite() || !jacobian.allFinite())
    throw NumericalError("parameter_statistics: a residual or its derivative is not finite at the optimum, so no standard errors can be computed");
  return parameter_statistics_of_factor(jacobian, r0.squaredNorm(), m, z, logarithmic);
}

ParameterStatistics parameter_statistics_of_factor(const Eigen::MatrixXd& factor, double squared_residual_norm, std::size_t m,
                                                   const std::vector<double>& z, const std::vector<bool>& logarithmic) {
  const std::size_t n = z.size();
  if (n == 0 || logarithmic.size() != n || factor.cols() != static_cast<Eigen::Index>(n) || m == 0)
    throw std::logic_error(fmt::format("parameter_statistics: {} coordinates, {} log flags, {} residuals and a {} x {} factor", n,
                                       logarithmic.size(), m, factor.rows(), factor.cols()));
  if (!std::isfinite(squared_residual_norm) || !factor.allFinite())
    throw NumericalError("parameter_statistics: a residual or its derivative is not finite at the optimum, so no standard errors can be computed");
  const Eigen::JacobiSVD<Eigen::MatrixXd> svd(factor, Eigen::ComputeFullV);
  const Eigen::VectorXd& s = svd.singularValues();  // min(m, n) of them, decreasing
  const Eigen::MatrixXd& v = svd.matrixV();         // n x n; columns beyond min(m, n) span null directions
  const auto nn = static_cast<Eigen::Index>(n);
  const double cutoff = kSingularTolerance * s(0);
  ParameterStatistics out;
  Eigen::VectorXd inverse_square = Eigen::VectorXd::Zero(nn);
  for (Eigen::Index k = 0; k < s.size(); ++k)
    if (s(k) > cutoff && s(k) > 0.0) {
      inverse_square(k) = 1.0 / (s(k) * s(k));
      ++out.rank;
    }
  out.residuals = static_cast<int>(m);
  const double s2 = m > static_cast<std::size_t>(out.rank) ? squared_residual_norm / static_cast<double>(m - static_cast<std::size_t>(out.rank))
                                                           : std::numeric_limits<double>::quiet_NaN();
  const Eigen::MatrixXd covariance = v * inverse_square.asDiagonal() * v.transpose();  // Cov_z / s^2

  for (Eigen::Index j = 0; j < nn; ++j) {
    double null_part = 0.0;
    for (Eigen::Index k = 0; k < nn; ++k)
      if (inverse_square(k) == 0.0) null_part += v(j, k) * v(j, k);
    out.identifiable.push_back(std::sqrt(null_part) <= kNullComponent);
  }
  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.correlation.assign(n, std::vector<double>(n, nan));
  for (std::size_t i = 0; i < n; ++i) {
    const auto ii = static_cast<Eigen::Index>(i);
    const double dp_dz = logarithmic[i] ? std::exp(z[i]) : 1.0;
    out.standard_error.push_back(out.identifiable[i] ? dp_dz * std::sqrt(s2 * covariance(ii, ii)) : std::numeric_limits<double>::infinity());
    out.correlation[i][i] = 1.0;
    for (std::size_t j = 0; j < n; ++j) {
      const auto jj = static_cast<Eigen::Index>(j);
      if (i != j && out.identifiable[i] && out.identifiable[j])
        out.correlation[i][j] = covariance(ii, jj) / std::sqrt(covariance(ii, ii) * covariance(jj, jj));
    }
  }
  // The practical tier (fit_statistics.hpp): standard errors beyond any useful range.
  for (std::size_t i = 0; i < n; ++i) {
    const double value = logarithmic[i] ? std::exp(z[i]) : std::abs(z[i]);
    if (!out.identifiable[i] || !(out.standard_error[i] > kUndeterminedRelativeError * value)) continue;
    out.identifiable[i] = false;
    out.standard_error[i] = std::numeric_limits<double>::infinity();
    for (std::size_t j = 0; j < n; ++j)
      if (j != i) out.correlation[i][j] = out.correlation[j][i] = nan;
  }
  // The practical bound in z units: 1000 |p| / |dp/dz| (1000 for a logarithmic coordinate).
  std::vector<double> bound;
  for (std::size_t i = 0; i < n; ++i) bound.push_back(kUndeterminedRelativeError * (logarithmic[i] ? 1.0 : std::abs(z[i])));
  group_undetermined(v, inverse_square, s2, bound, out);
  return out;
}

}  // namespace rheo::runtime
