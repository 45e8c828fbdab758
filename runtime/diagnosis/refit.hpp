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

// Stage 1: the ADDED parameters alone from START; stage 2: every free parameter (KEPT and ADDED)
// from there (DiagnoseSettings budgets). The result counts the evaluations of both.
FitResult staged_refit(const Network& start, const std::vector<int>& kept, const std::vector<int>& added, const std::vector<FitDataSet>& data,
                       const DiagnoseSettings& settings);

}  // namespace rheo::runtime::diagnosis
