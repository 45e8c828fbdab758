// The sentences `rheo diagnose` says about its evidence: why an effect was named (or none),
// where the residual lies, and what was added, with numbers and units.
#pragma once

#include "runtime/diagnosis/diagnose.hpp"

#include <string>
#include <vector>

namespace rheo::runtime::diagnosis {

// What the residual pattern says about EFFECT, e.g. "the amplitude dependence is not the same
// at every frequency: the interaction holds 62 % of the residual".
std::string pattern_sentence(Effect effect, const ResidualPatterns& patterns);

// Why WINNER was chosen: its pattern sentence, its screening share, the gap and BIC.
std::string effect_reason(const Diagnosis& diagnosis, const CandidateOutcome& winner);

// Why nothing was added: no candidate screened above the threshold, or none earned its parameters.
std::string none_reason(const Diagnosis& diagnosis, const DiagnoseSettings& settings);

// "cap.fy = 60.74 N, arm.k = 520 N/mm, arm.tau = 5.036 ms": the fitted parameters of ELEMENT in
// their written units.
std::string added_summary(const FitResult& refit, const std::string& element);

// The statement of root element ELEMENT in TEXT (the source of model SOURCE.model), one string per line.
std::vector<std::string> statement_lines(const std::string& text, const ModelSource& source, const std::string& element);

// Lines describing where the model and the data disagree (report "where the model misses").
std::vector<std::string> pattern_lines(const ResidualPatterns& patterns);

}  // namespace rheo::runtime::diagnosis
