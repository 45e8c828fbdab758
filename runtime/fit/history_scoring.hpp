// Fits whose data are all measured histories, scored a block of samples at a time: the
// separable solve of the force scales and the standard errors hold no per-sample array beyond
// the data (a 1e7-sample history is 10^7 residuals; its design matrix or Jacobian alone would
// be 80 MB a column).
//
// Every network the computation needs (the shape's scales and their differences; the optimum
// and its central differences) is simulated in lockstep over the history (HistoryForceStream:
// the numbers of history_force), and each block's rows of the linear least-squares problem go
// into a StreamingLeastSquares (its triangular factor of [A | b], streaming_least_squares.hpp).
// The rows are those of the whole-vector paths (fit_scoring.hpp's residuals
// r_j = sqrt(w / M) / max|F_exp| (F_j + c - F_exp,j), force_offset.hpp's offsets), so both
// give the same minimiser and statistics up to rounding (tests/runtime/fit/history_scoring_test.cpp
// compares them).
#pragma once

#include "runtime/fit/force_offset.hpp"
#include "runtime/fit/separable_fit.hpp"

#include <functional>
#include <vector>

namespace rheo::runtime {

// Whether every data set is a history (and there is one at least).
bool all_histories(const std::vector<FitDataSet>& data);

// solve_scales (separable_fit.hpp) for data that are all histories: one pass of scales + 1
// networks in lockstep. The rows, per sample j of file f with free offsets first:
//   [ s_f e_f | s_f (F_k,j - F_0,j) / h_k ] x ~ -s_f (F_0,j + c_f - F_exp,j)
// (F_0 the force at the start scales s0, F_k at s0 + h_k e_k, c_f a declared offset; e_f the
// indicator of a file with a free offset, its offset an unbounded unknown: eliminating it is
// eliminating the mean, force_offset.hpp). With R = [[R_oo, R_os], [0, R_ss]] the offsets'
// rows are met exactly for any scales, so the scales are the bounded solve of (R_ss, c_s) and
// the objective there is || R_ss (s - s0) - c_s ||^2 + rest^2. The history residuals are the
// same under either objective, and affine in s: the solve is the minimum, with no
// Levenberg-Marquardt after it.
ScaleSolution solve_history_scales(const Network& network, const std::vector<int>& scales, const std::vector<double>& lower,
                                   const std::vector<double>& upper, const std::vector<FitDataSet>& data, const ScoreSettings& score);

// statistics_with_offsets (force_offset.hpp) for data that are all histories, NETWORK_AT(z)
// the model at search coordinates z: a first pass over the optimum for the free offsets (their
// means, as force_offset computes them), then one of the optimum and its 2 n central
// differences in lockstep (the steps of fit_statistics.hpp), each sample's Jacobian row into
// the factor whose SVD gives the statistics. Throws what statistics_with_offsets throws.
StatisticsWithOffsets history_statistics(const std::function<Network(const std::vector<double>&)>& network_at, const std::vector<FitDataSet>& data,
                                         const ScoreSettings& score, const std::vector<double>& z, const std::vector<bool>& logarithmic);

}  // namespace rheo::runtime
