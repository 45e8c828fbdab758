// Standard errors and correlations of fitted parameters at a least-squares optimum
// (Gauss-Newton linearisation; the usual asymptotic statistics of non-linear regression).
//
// At the optimum z (n search coordinates) with weighted residuals r(z) (m entries, objective
// sum r_i^2):
//   J_ij = (r_i(z + h_j e_j) - r_i(z - h_j e_j)) / (2 h_j),  h_j = 1e-6 max(1, |z_j|)
//     (central differences, error O(h^2) + O(eps |r| / h); h_j is taken as the representable
//     difference of the two evaluation points, so it is exact in floating point)
//   J = U S V^T (SVD, V n x n); singular values s_k <= 1e-8 s_max count as zero (the finite-
//     difference noise of J is ~1e-10 relative, so below 1e-8 a direction is not resolved);
//     rank = the number of the others
//   s^2 = |r|^2 / (m - rank)                         (= |r|^2 / (m - n) at full rank)
//   Cov_z = s^2 (J^T J)^+ = s^2 V S^+2 V^T           (Moore-Penrose pseudo-inverse)
// A coordinate z_j is identifiable when it has no component along the null space of J:
// |P_null e_j| = sqrt(sum over zero s_k of V_jk^2) <= 1e-6. For identifiable coordinates the
// pseudo-inverse entries are the exact (co)variances of estimable quantities even when other
// coordinates are not identifiable; a non-identifiable coordinate's variance is unbounded.
// A coordinate whose standard error exceeds 1000 times its parameter's value counts as not
// identifiable too: the data leave it free within any range a user cares about (a direction
// the finite differences of a time-stepped or event-driven response resolve only to their
// noise, as two stiffnesses in series, r = +-1; #22 item 7).
// Groups: the non-identifiable coordinates coupled through the undetermined subspace (J's null
// directions and, for each practically non-identifiable coordinate, the direction that carries
// most of its variance): they act only together; a group of g coordinates spanning d
// undetermined directions leaves the data g - d combinations of them (d = g - 1: one).
// Parameter space (delta method): p_j = exp(z_j) for logarithmic coordinates, else p_j = z_j,
//   SE(p_j) = |dp_j/dz_j| sqrt(Cov_z,jj),  dp/dz = p_j (log) or 1,
//   correlation(p_i, p_j) = Cov_z,ij / sqrt(Cov_z,ii Cov_z,jj)  (invariant under the monotone
//   increasing maps above).
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <functional>
#include <vector>

namespace rheo::runtime {

struct ParameterStatistics {
  std::vector<double> standard_error;            // parameter units; +inf when not identifiable,
                                                 // NaN when residuals <= rank (no s^2)
  std::vector<std::vector<double>> correlation;  // n x n, diagonal 1; NaN off the diagonal in
                                                 // rows and columns of non-identifiable parameters
                                                 // (and where a variance is 0: a perfect fit)
  std::vector<bool> identifiable;
  std::vector<std::vector<int>> together;  // groups (2 or more) of non-identifiable coordinates that act only together
  std::vector<int> undetermined;           // per group: the undetermined directions it spans, 1..size
  int rank = 0;                            // numerical rank of J
  int residuals = 0;                       // m
  bool has_noise_estimate() const { return residuals > rank; }
};

// `residuals` is called 2 n + 1 times; `logarithmic` has n entries. When m <= rank no degree of
// freedom is left for s^2: identifiability and correlations are still given (they do not
// depend on s^2), standard errors of identifiable parameters are NaN. Throws
// std::logic_error when sizes disagree or r changes size between calls; NumericalError when a
// residual is not finite.
ParameterStatistics parameter_statistics(const std::function<std::vector<double>(const std::vector<double>&)>& residuals,
                                         const std::vector<double>& z, const std::vector<bool>& logarithmic);
// The same from the residuals r0 at z and their Jacobian dr/dz there (m x n), however found
// (e.g. by sensitivities, harmonic_jacobian.hpp).
ParameterStatistics parameter_statistics(const Eigen::VectorXd& r0, const Eigen::MatrixXd& jacobian, const std::vector<double>& z,
                                         const std::vector<bool>& logarithmic);
// The same from a matrix with J's singular values and right singular vectors (J itself, or the
// triangular factor R of J = Q R that a StreamingLeastSquares gives without holding J), |r0|^2
// and m, the number of residuals.
ParameterStatistics parameter_statistics_of_factor(const Eigen::MatrixXd& factor, double squared_residual_norm, std::size_t residuals,
                                                   const std::vector<double>& z, const std::vector<bool>& logarithmic);

// The central differences' relative step (h_j above), for callers that difference themselves.
inline constexpr double kStatisticsRelativeStep = 1e-6;
// The NumericalError where a residual near the optimum is not finite.
inline constexpr const char* kStatisticsNotFinite =
    "parameter_statistics: a residual is not finite near the optimum, so no standard errors can be computed; a "
    "parameter is likely at the edge of the range the model can be simulated in: fix it or narrow its bounds";

}  // namespace rheo::runtime
