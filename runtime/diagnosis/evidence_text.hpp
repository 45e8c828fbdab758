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

// Why WINNER was chosen: its pattern sentence, its screening share, the gap and BIC; and every
// refitted candidate of another effect that earned and came within PARSIMONY of the winner's gap
// (the data do not tell them apart: the winner has no more parameters, or a gap lower by more
// than parsimony, DiagnoseSettings::parsimony).
std::string effect_reason(const Diagnosis& diagnosis, const CandidateOutcome& winner, double parsimony);

// The candidates effect_reason names as fitting about as well as WINNER: of each other effect,
// its best refitted candidate that earned (BIC below the model's, its resonance resolved) and
// whose gap is within PARSIMONY of WINNER's, unless WINNER has more parameters and a
// decisively lower noise-weighted BIC (criterion.hpp decisively_lower: the data tell them
// apart); in the order of DIAGNOSIS.candidates.
std::vector<const CandidateOutcome*> alike_candidates(const Diagnosis& diagnosis, const CandidateOutcome& winner, double parsimony);

// Why nothing was added and the residual is noise: no candidate screened above the threshold, or
// none earned its parameters; and the gap against the noise estimate.
std::string none_reason(const Diagnosis& diagnosis, const DiagnoseSettings& settings);

// Why the verdict is unexplained: how far the gap is above the noise, where the residual lies,
// what it resembles, and the best candidate's numbers.
std::string unexplained_reason(const Diagnosis& diagnosis);

// The refitted candidate of the lowest BIC, or null; where the criterion is noise-weighted, of
// those at their likelihood's maximum where any is (as the model's BIC is), so that the BICs a
// reason compares are alike. The best candidate the `none` and `unexplained` reasons name.
const CandidateOutcome* best_candidate(const Diagnosis& diagnosis);

// The noise estimate in words: "measurement noise estimated from the residual's roughness over
// the grid: 1.02 % in stiffness, 0.151 deg in phase; it leaves err (6.1) = 0.0021 (+-8 %), and the
// gap is 1.04 times that"; empty without an estimate.
std::string noise_sentence(const Diagnosis& diagnosis);

// "cap.fy = 60.74 N, arm.k = 520 N/mm, arm.tau = 5.036 ms": the fitted parameters of ELEMENT in
// their written units.
std::string added_summary(const FitResult& refit, const std::string& element);

// The statement of root element ELEMENT in TEXT (the source of model SOURCE.model), one string per line.
std::vector<std::string> statement_lines(const std::string& text, const ModelSource& source, const std::string& element);

// Lines describing where the model and the data disagree (report "where the model misses").
std::vector<std::string> pattern_lines(const ResidualPatterns& patterns);

}  // namespace rheo::runtime::diagnosis
