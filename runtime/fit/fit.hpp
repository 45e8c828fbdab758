// Parameter identification: `rheo fit` without the command line.
//
// The free parameters (indices into the model's parameters) are searched in coordinates
// z = ln p when their bounds are positive (relative changes weigh alike), z = p otherwise;
// derived parameters (c = k tau, fy = k uy) follow their inputs. The objective is the sum of
// squares of fit_scoring.hpp's residuals, minimised by fit_search.hpp's strategy.
//
// Methods (fit_scoring.hpp): exact and approximate minimise with that model response;
// corrected follows Table 5.1: fit the approximation, compute the correction factors
// (5.2, 5.3) by the exact response at that optimum, and fit the calibrated approximation (5.4)
// from there. The exact method with the default strategy, on harmonic data and a network the
// approximation covers, first runs the corrected fit as a cheap surrogate (with a budget of its
// own: an approximate evaluation costs about 1/30 of an exact one) and adds its optimum to the
// starts of the exact search, so that exact ends no worse than corrected.
//
// Reported whatever the method: phi (5.1) and err (6.1) over all harmonic points by the exact
// response at the fitted parameters, per file too; for histories the RMS force residual
// relative to max|F|, with the data line's force offset (force_offset.hpp: a free one is
// eliminated exactly at every evaluation and reported with its standard error). Standard errors and correlations come from the Jacobian of the
// method's residuals at the optimum (fit_statistics.hpp).
#pragma once

#include "runtime/io/fit_data.hpp"
#include "runtime/fit/fit_scoring.hpp"
#include "runtime/fit/fit_search.hpp"
#include "runtime/fit/data_set_fit.hpp"
#include "runtime/fit/fit_statistics.hpp"
#include "runtime/network/network.hpp"
#include "runtime/fit/objective.hpp"

#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime {

struct FitSettings {
  ScoreSettings score;
  SearchSettings search;
  // With a time history among the data and one yeoh spring in the root block whose constants
  // are free: start them at the least-squares fit to the mean curve of the history's largest
  // loop (eqs. 5.28-5.32), as the thesis identifies them, before searching.
  bool yeoh_start_from_history = true;
  // Exact method, where every prediction is affine in some free parameters (force_scales.hpp,
  // separable_fit.hpp): solve those exactly inside the search over the others.
  bool separable = true;
  // Exact method, where every prediction is a closed-form harmonic point of a network with all
  // its elements in the root block (harmonic_jacobian.hpp): Levenberg-Marquardt takes its
  // Jacobians from the analytic sensitivities (one evaluation each) instead of n differenced
  // evaluations.
  bool sensitivities = true;
  // Exact method, every data set a history: where the differenced Jacobian's m x n doubles
  // would take more bytes than this, Levenberg-Marquardt takes it reduced to n x n while the
  // samples stream past (history_jacobian.hpp) instead of holding it and n moved residual
  // vectors. 0: always reduced.
  std::size_t whole_jacobian_bytes = std::size_t{64} << 20;
  // Standard errors and correlations at the optimum (a Jacobian: about 2 evaluations per free
  // parameter); off, FitResult::statistics stays empty.
  bool statistics = true;
  // Wall-clock bound of the whole fit [s]: the searches stop in time to leave the standard
  // errors room at the cost per evaluation measured so far, and the fit returns the best point
  // found (FitResult::time_limited). Absent, or above 1e8 s (three years): none.
  std::optional<double> time_limit;
  // More starting points (each every model parameter, internal units; clamped into the bounds):
  // the default strategy runs a local search from each too (fit_search.hpp), as from the start;
  // not on the separable path, whose search is over the shape parameters only.
  std::vector<std::vector<double>> extra_starts;
  std::function<void(const SearchProgress&)> progress;  // called after every evaluation
  const std::atomic<bool>* interrupt = nullptr;         // set (e.g. by SIGINT) to stop with the best so far
};

struct FitResult {
  Network network;  // the model with the fitted values
  std::vector<int> free{};
  std::vector<double> start_values{};  // all parameters, where the search started (after the yeoh start)
  std::vector<int> yeoh_started{};     // the parameters whose start the yeoh start set (FitSettings::yeoh_start_from_history)
  double objective = 0.0;              // the minimised sum of squares, with the method's response
  double phi = 0.0;                    // eq. 5.1 over all harmonic points (exact response)
  double err = 0.0;                    // eq. 6.1 over all harmonic points; 0 when there are none
  std::vector<DataSetFit> datasets{};
  ParameterStatistics statistics{};  // per free parameter, in parameter units
  int evaluations = 0;
  int non_finite = 0;           // rejected evaluations: NaN, inf, or not simulable
  std::string first_failure{};  // why the first evaluation that could not be simulated failed
  double wall_seconds = 0.0;
  std::string status{};
  bool interrupted = false;
  bool time_limited = false;         // a search stopped at FitSettings::time_limit
  std::vector<std::string> notes{};  // what the fit did beyond the search (e.g. the yeoh start)
};

// Indices of the parameters declared with bounds.
std::vector<int> bounded_parameters(const Network& network);

// Preconditions (std::logic_error otherwise; the front end reports them to the user first):
// `free` is non-empty and names parameters with bounds, `data` is non-empty. Throws UsageError
// when the approximate or corrected method meets harmonic data and a structure the
// approximation cannot take (approximation_misfit), and what simulating the model throws.
FitResult fit(const Network& start, const std::vector<int>& free, const std::vector<FitDataSet>& data, const FitSettings& settings);

}  // namespace rheo::runtime
