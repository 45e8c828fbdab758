// The differenced Jacobian of a fit whose data are all measured histories, reduced to n rows
// while the samples stream past: the Levenberg-Marquardt search (levenberg_marquardt.hpp)
// holds no m x n matrix and no n moved residual vectors for a long history (at 1e7 samples,
// 80 MB a column), only n x n numbers.
//
// At search coordinates z with forward steps h_k (levenberg_marquardt.cpp chooses them), the
// base network and the n moved ones (z + h_k e_k; h_k = 0: none, a zero column) are simulated
// in lockstep (history_blocks.hpp), and each sample j of file f gives the row
//   [ s_f e_f | s_f (F_k,j - F_0,j) / h_k ]  x  ~  -s_f (F_0,j + c_f - F_exp,j)
// of a StreamingLeastSquares (the factor of [A | b], streaming_least_squares.hpp), with free
// offsets first as in history_scoring.hpp (s_f = sqrt(w_f / M_f) / max|F_exp,f|, c_f a declared
// offset, e_f the indicator of a file whose offset is free). Its factor [[R_oo, R_os],
// [0, R_ss]], [c_o; c_s] meets the offsets' rows exactly for any d, so for the residuals r of
// fit_scoring.hpp at z (a free offset at its least-squares value, the mean) and the differenced
// Jacobian J of those residuals,
//   || J d + r ||^2 = || R_ss d - c_s ||^2 + rest^2,   || r ||^2 = || c_s ||^2 + rest^2,
// which is LeastSquaresProblem::reduced_jacobian's form with R = R_ss and c = -c_s. Both sides
// are the same quadratic in d up to rounding: the whole-vector Jacobian's QR and this factor
// give the same damped steps to ~1e-12 relative (history_jacobian_test).
#pragma once

#include "runtime/fit/fit_scoring.hpp"

#include <Eigen/Core>

#include <functional>
#include <optional>
#include <vector>

namespace rheo::runtime {

struct ReducedHistoryJacobian {
  Eigen::MatrixXd r;                 // n x n, upper triangular: R_ss
  Eigen::VectorXd c;                 // n: -c_s
  std::vector<double> moved_values;  // phi = || r ||^2 at each moved point z + h_k e_k (NaN where h_k = 0)
};

// NETWORK_AT(z): the model at search coordinates z. nullopt where a network's forces are not
// finite, or a simulation throws NumericalError (the caller differences the columns one by one
// instead, where each can be taken the other way).
std::optional<ReducedHistoryJacobian> reduced_history_jacobian(const std::function<Network(const std::vector<double>&)>& network_at,
                                                               const std::vector<FitDataSet>& data, const ScoreSettings& score,
                                                               const std::vector<double>& z, const std::vector<double>& steps);

// phi = || r ||^2 of the history residuals of fit_scoring.hpp (a free offset at its
// least-squares value) for NETWORK, a block of samples at a time: no per-sample array. Throws
// NumericalError where the forces are not finite or cannot be simulated.
double history_phi(const Network& network, const std::vector<FitDataSet>& data, const ScoreSettings& score);

// The residuals' count m of all-history DATA (one a sample).
std::size_t history_residual_count(const std::vector<FitDataSet>& data);

}  // namespace rheo::runtime
