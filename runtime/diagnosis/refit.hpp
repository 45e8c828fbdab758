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

// BASE as one local BOBYQA search of at most EVALUATIONS, without statistics or a Yeoh start.
FitSettings local_search(const FitSettings& base, int evaluations);

// Stage 1: the ADDED parameters sampled over the range the data support (global_look.hpp), then
// searched by Levenberg-Marquardt from START and the best samples;
// stage 2: every free parameter (KEPT and ADDED) by Levenberg-Marquardt from the best of stage
// 1 and from START, the better kept (DiagnoseSettings budgets; a time limit in
// settings.fit.time_limit is shared: half to stage 1). The result counts the evaluations of both.
FitResult staged_refit(const Network& start, const std::vector<int>& kept, const std::vector<int>& added, const std::vector<FitDataSet>& data,
                       const DiagnoseSettings& settings);

}  // namespace rheo::runtime::diagnosis
