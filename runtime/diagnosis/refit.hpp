// The refits of rheo diagnose (diagnose.hpp, step 3) and their budgets: how much work one
// evaluation of a candidate costs, how many evaluations the budget affords, and the two-stage
// refit of a candidate's new parameters, then of every free one.
#pragma once

#include "runtime/diagnosis/diagnose.hpp"

#include <vector>

namespace rheo::runtime::diagnosis {

// Evaluations DiagnoseSettings::refit_work affords at the work per evaluation of NETWORK, within
// [floor, max_evaluations].
int affordable_evaluations(const Network& network, const std::vector<FitDataSet>& data, const DiagnoseSettings& s, int floor);

// Jacobians a Levenberg-Marquardt search of n parameters gets where the work budget affords
// fewer: each costs n + 1 evaluations (n differenced columns and the step). Diagnose's local
// searches of 4 to 17 parameters on the hydrobushing converge, or crawl by less than 1e-4 of
// their objective a Jacobian, within about ten (docs/performance.md, 2026-11-27).
inline constexpr int kLocalJacobians = 10;

// The polish of the chosen model (diagnose.hpp, step 5) starts where a local search of every
// free parameter ended and ends where a Jacobian's step lowers the objective by less than this
// share of it (the gap by less than half that, below the four digits a diagnosis reports; the
// verdict is taken before): on the hydrobushing the polish otherwise crawled nine Jacobians at
// 1e-5 each (docs/performance.md, 2026-11-27 session 4).
inline constexpr double kPolishCrawl = 1e-4;

// BASE as one local search of at most EVALUATIONS from its start, without statistics or a Yeoh
// start: Levenberg-Marquardt on the residual vector (rheo fit's default local method,
// fit_search.hpp: half the budget, then a polish from the best point with the rest), BOBYQA
// where the objective has no residual vector.
FitSettings local_search(const FitSettings& base, int evaluations);

// Stage 1: the ADDED parameters sampled over the range the data support (global_look.hpp), then
// searched by Levenberg-Marquardt from START and the best samples, together with the
// stiffnesses of the linear springs in the root block among KEPT (the stiffness the new element
// takes over: free play engaging at the larger amplitudes, whose stiffening the fitted springs
// had spread over every amplitude);
// stage 2: every free parameter (KEPT and ADDED) by Levenberg-Marquardt from the best of stage
// 1 and from START, the better kept (DiagnoseSettings budgets; a time limit in
// settings.fit.time_limit is shared: half to stage 1); the better search of stage 2, where its
// budget ran out while it still descended, continues once with the same budget, to a crawl of
// kPolishCrawl. Both starts of stage 2 descend the
// residuals with the same budget, so that the result does not hang on which of the model's
// equally good fits START holds (refit_test.cpp). The result counts the evaluations of both.
FitResult staged_refit(const Network& start, const std::vector<int>& kept, const std::vector<int>& added, const std::vector<FitDataSet>& data,
                       const DiagnoseSettings& settings);

}  // namespace rheo::runtime::diagnosis
