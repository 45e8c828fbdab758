// The search strategy of `rheo fit` over the free parameters' search coordinates z (ln p for
// parameters with positive bounds, p otherwise), within box bounds.
//
// Default (no algorithm named): a global look, then local polish.
//   1. sample: max(10 n, 40) points (or `samples`) of a Halton sequence (randomly shifted by the seed) over
//      the box z0 -+ ln 10 (a decade either side of the start; a quarter of the bounds for
//      linear coordinates), clipped to the bounds;
//   2. local: BOBYQA (Levenberg-Marquardt for a least-squares objective given by its residuals,
//      levenberg_marquardt.hpp) from the start, from any extra starts given (e.g. a surrogate's optimum)
//      and from the best samples, `starts` searches in all (at least the start and the extra
//      ones), sharing the evaluation budget;
//   3. polish: the local method again from the best point found, with a fresh trust region.
// A local algorithm named (bobyqa, sbplx, neldermead) takes the local method's place; a global one
// (direct_l, crs2, isres, mlsl) searches the whole box with half the budget, then BOBYQA polishes.
// The same seed gives the same result, evaluation for evaluation, for every `threads`.
//
// Budget: the start is always evaluated first; after it, no evaluation is made beyond
// max_evaluations in all (stages share what is left; an NLopt stage that would take the total
// beyond it, as DIRECT-L can overrun its own maxeval, is stopped), so
// 1 <= evaluations <= max(1, max_evaluations).
// The best point seen is kept: when `interrupt` becomes true (Ctrl-C) the search stops at the
// next evaluation (never before the start's) and returns it, with interrupted = true.
// With a `deadline`, the budget is cut to the evaluations the time left affords at the mean cost
// so far (measured after the start and again before each local search and the polish), less
// `reserve_evaluations` (the work the caller still has to do after the
// search, such as standard errors), so the stages share what can run; and no evaluation begins
// unless the time left covers it and the reserve at the mean cost so far. The search then
// returns its best point with out_of_time = true and status "TIME_LIMIT_REACHED".
#pragma once

#include "runtime/fit/optimizer.hpp"

#include <Eigen/Core>

#include <atomic>
#include <chrono>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime {

// dr/dz of the residuals at z (residuals x coordinates), e.g. by sensitivities
// (harmonic_jacobian.hpp); a matrix with no columns where it is not available there.
using ResidualJacobian = std::function<Eigen::MatrixXd(const std::vector<double>& z)>;

// A differenced Jacobian of the residuals at z with forward steps STEPS (0: a zero column)
// reduced to n rows (levenberg_marquardt.hpp, LeastSquaresProblem::reduced_jacobian), and phi
// at each moved point z + steps_k e_k (NaN where steps_k = 0); nullopt where it cannot be formed.
struct ReducedJacobian {
  Eigen::MatrixXd r;
  Eigen::VectorXd c;
  std::vector<double> moved_values;
};
using ReducedResidualJacobian = std::function<std::optional<ReducedJacobian>(const std::vector<double>& z, const std::vector<double>& steps)>;

struct SearchSettings {
  std::optional<Algorithm> algorithm;  // nullopt: the default strategy above
  int max_evaluations = 20000;         // over all stages
  int starts = 3;
  int samples = -1;  // default strategy's sample count; -1: max(10 n, 40)
  unsigned long seed = 1;
  double tolerance = 1e-10;  // relative, on z (local stages)
  // Levenberg-Marquardt stages (levenberg_marquardt.hpp crawl_tolerance): end where a Jacobian's
  // step lowered the objective by less than this share of it; 0: never.
  double crawl_tolerance = 0.0;
  std::vector<std::vector<double>> extra_starts;  // default strategy: local searches from these too
  std::optional<std::chrono::steady_clock::time_point> deadline;
  int reserve_evaluations = 0;
  // Independent evaluations (a differenced Jacobian's columns, the samples) made at once, each
  // whole on one thread (search_tracker.hpp); 0: every hardware thread. Results do not depend
  // on it. Above 1 the objective or residuals are called from several threads at once and must
  // be safe for that.
  int threads = 1;
  // Optional, for search_least_squares: the Levenberg-Marquardt stages take their Jacobians from
  // it instead of differencing n evaluations; each call counts as one evaluation.
  ResidualJacobian jacobian;
  // Optional, for search_least_squares without `jacobian`: the Levenberg-Marquardt stages take
  // their differenced Jacobians from it, reduced, instead of n residual vectors (residuals too
  // many to hold n times: history_jacobian.hpp); each call counts as its moved points'
  // evaluations, recorded with their values.
  ReducedResidualJacobian reduced_jacobian;
};

struct SearchProgress {
  int evaluations = 0;
  double best = 0.0;       // best objective so far
  const char* stage = "";  // "start", "sample", "local", "global" or "polish"
  int limit = 0;           // the evaluations this search may reach: its budget, or what its deadline affords
  double seconds = 0.0;    // wall time since the search began [s]
};

struct SearchResult {
  std::vector<double> z;  // the best point evaluated (the start when interrupted before a finite one)
  double value = 0.0;     // the objective at z; +inf when interrupted before a finite evaluation
  int evaluations = 0;
  int non_finite = 0;         // evaluations that returned NaN or inf, or threw NumericalError (any stage)
  std::string first_failure;  // the message of the first NumericalError, if any
  std::string status;         // the last local stage's NLopt result, "MAXEVAL_REACHED" when the budget
                              // ran out before or during a stage, "TIME_LIMIT_REACHED", or "interrupted"
  bool interrupted = false;
  bool out_of_time = false;
};

// The residuals whose sum of squares is the objective of search_least_squares.
using Residuals = std::function<std::vector<double>(const std::vector<double>&)>;

// `logarithmic[j]`: coordinate j is ln p (sampled a decade either side of the start).
// Throws NumericalError, naming the first failure, when no evaluation of an uninterrupted
// search is finite: there is no point to report.
SearchResult search(const Objective& objective, const std::vector<double>& start, const std::vector<double>& lower,
                    const std::vector<double>& upper, const std::vector<bool>& logarithmic, const SearchSettings& settings,
                    const std::function<void(const SearchProgress&)>& progress = {}, const std::atomic<bool>* interrupt = nullptr);

// The same search of the objective sum_i r_i(z)^2; with no algorithm named its local stages
// are Levenberg-Marquardt on the residuals (a Jacobian costs n evaluations, each counted).
SearchResult search_least_squares(const Residuals& residuals, const std::vector<double>& start, const std::vector<double>& lower,
                                  const std::vector<double>& upper, const std::vector<bool>& logarithmic, const SearchSettings& settings,
                                  const std::function<void(const SearchProgress&)>& progress = {}, const std::atomic<bool>* interrupt = nullptr);

// The same search where the residuals are too many to hold even once (a long history's):
// OBJECTIVE gives phi = sum_i r_i(z)^2 of RESIDUAL_COUNT residuals alone, and with no algorithm
// named the local stages are Levenberg-Marquardt taking each Jacobian reduced from
// settings.reduced_jacobian (needed; it counts its moved points as evaluations).
SearchResult search_least_squares_by_value(const Objective& objective, std::size_t residual_count, const std::vector<double>& start,
                                           const std::vector<double>& lower, const std::vector<double>& upper, const std::vector<bool>& logarithmic,
                                           const SearchSettings& settings, const std::function<void(const SearchProgress&)>& progress = {},
                                           const std::atomic<bool>* interrupt = nullptr);

}  // namespace rheo::runtime
