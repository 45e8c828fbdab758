// The force scales of a fit solved exactly for given shape parameters (variable projection).
//
// With the shape held, every prediction is affine in the scales s (force_scales.hpp):
//   P(s) = P(s0) + sum_j (s_j - s0_j) B_j,   B_j = (P(s0 + h_j e_j) - P(s0)) / h_j
// (exact: the differences of an affine map), so n + 1 model evaluations give the model's
// response for every s. Its quantities: K'_1 and K''_1 per harmonic point (measures_from gives
// K and phase by the file's definition), F per history sample.
// Then, within the scales' bounds:
//  1. the least-squares objective's residuals (fit_scoring.hpp) are affine in s: one bounded
//     linear least-squares solve (bounded_least_squares.hpp) is their global minimum;
//  2. for the phi objective (eq. 5.38: relative K and sin(phase), not affine in s) that solution
//     starts a Levenberg-Marquardt search on the exact residuals, each step a bounded linear
//     least-squares problem (levenberg_marquardt.hpp, tolerances in docs/numerics.md).
// The shape search above it (fit.cpp) therefore sees the objective minimised over the scales,
// a function of fewer, and only the non-linear, parameters; with every shape parameter held a
// fit is this one solve.
#pragma once

#include "runtime/fit/fit_scoring.hpp"
#include "runtime/io/fit_data.hpp"
#include "runtime/network/network.hpp"

#include <vector>

namespace rheo::runtime {

// Whether every file's prediction is affine in the force scales by the exact method: histories,
// and harmonic files under the first-harmonic definition or of a linear network.
bool predictions_affine(const Network& network, const std::vector<FitDataSet>& data, const ScoreSettings& score);

struct ScaleSolution {
  std::vector<double> values;  // every model parameter, the scales solved
  double objective = 0.0;      // the fit's objective (sum of squared residuals) there
  int evaluations = 0;         // model evaluations made (scales + 1)
};

// `scales`: indices of model parameters that are force scales, with their bounds `lower`,
// `upper` (internal units). The other parameters keep network's values. Throws what
// evaluating the model throws (NumericalError for a point that cannot be simulated).
// Data that are all histories are solved a block of samples at a time, holding no
// per-sample array (history_scoring.hpp: the same minimum up to rounding).
ScaleSolution solve_scales(const Network& network, const std::vector<int>& scales, const std::vector<double>& lower,
                           const std::vector<double>& upper, const std::vector<FitDataSet>& data, const ScoreSettings& score);

}  // namespace rheo::runtime
