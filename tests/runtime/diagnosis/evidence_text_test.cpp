// The sentences of runtime/diagnosis/evidence_text.hpp: a named effect's reason says which other
// refitted candidates fit about as well (within the parsimony margin of its gap), and only those.
#include "runtime/diagnosis/evidence_text.hpp"
#include "runtime/diagnosis/trial.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace evidence_text_test {

using namespace rheo::runtime::diagnosis;

namespace {

CandidateOutcome refitted(Effect effect, Shape shape, double gap, double criterion, int parameters) {
  CandidateOutcome c;
  c.screened.effect = effect;
  c.screened.trial.effect = effect;
  c.screened.trial.shape = shape;
  c.screened.trial.stiffness = 100.0, c.screened.trial.slip = 0.25;
  c.screened.gain = 0.6;
  c.refitted = true;
  c.gap_after = gap, c.criterion = criterion, c.parameters = parameters;
  return c;
}

}  // namespace

TEST_CASE("a named effect's reason names the candidates of other effects that fit about as well") {
  Diagnosis d;
  d.gap_name = "err (6.1)";
  d.gap_before = 0.05, d.criterion_before = 1000.0;
  d.candidates.push_back(refitted(Effect::nonlinear_elasticity, Shape::yeoh, 0.0103, 300.0, 7));
  d.candidates.push_back(refitted(Effect::backlash, Shape::gapped_spring, 0.0096, 280.0, 8));         // within 10 %: named
  d.candidates.push_back(refitted(Effect::amplitude_dependence, Shape::friction, 0.0125, 400.0, 7));  // 21 % above: not
  d.candidates.push_back(refitted(Effect::nonlinear_elasticity, Shape::yeoh, 0.0100, 290.0, 7));      // the winner's effect: not
  CandidateOutcome no_gain = refitted(Effect::inertia, Shape::mass, 0.0101, 1200.0, 8);               // BIC above the model's: not
  d.candidates.push_back(no_gain);
  const std::string reason = effect_reason(d, d.candidates.front(), 0.1);
  CAPTURE(reason);
  CHECK(reason.find("behind free play") != std::string::npos);
  CHECK(reason.find("(backlash) fits about as well (err (6.1) 0.0096, BIC 280.0, 1 parameter more): these data do not tell the two apart") !=
        std::string::npos);
  CHECK(reason.find("amplitude-dependence") == std::string::npos);
  CHECK(reason.find("inertia") == std::string::npos);
  CHECK(reason.find("fits about as well") == reason.rfind("fits about as well"));  // once
  // Named backlash (0.0096): the yeoh's better refit (0.0100) is within 10 %, and named once
  // for its effect; within 2 % (0.00979) none is.
  const std::string backlash = effect_reason(d, d.candidates[1], 0.1);
  CAPTURE(backlash);
  CHECK(backlash.find("(nonlinear-elasticity) fits about as well (err (6.1) 0.01, BIC 290.0, 1 parameter fewer)") != std::string::npos);
  CHECK(backlash.find("fits about as well") == backlash.rfind("fits about as well"));
  CHECK(effect_reason(d, d.candidates[1], 0.02).find("fits about as well") == std::string::npos);
  // The same candidates as a list (Diagnosis::alike, JSON `alike`): for the yeoh the backlash
  // refit, for the backlash the yeoh's better refit only, within 2 % none.
  const auto for_yeoh = alike_candidates(d, d.candidates.front(), 0.1);
  REQUIRE(for_yeoh.size() == 1);
  CHECK(for_yeoh.front() == &d.candidates[1]);
  const auto for_backlash = alike_candidates(d, d.candidates[1], 0.1);
  REQUIRE(for_backlash.size() == 1);
  CHECK(for_backlash.front() == &d.candidates[3]);
  CHECK(alike_candidates(d, d.candidates[1], 0.02).empty());
}

// Under a noise-weighted criterion, a winner with more parameters whose BIC is lower than a
// within-margin candidate's by more than 10 times its residual's overdispersion
// (criterion.hpp decisively_lower) is not "alike" it: the reason says the data decide.
TEST_CASE("a named effect's reason says where the data decide against a candidate with fewer parameters that fits within the margin") {
  Diagnosis d;
  d.gap_name = "err (6.1)";
  d.gap_before = 0.05, d.criterion_before = 1000.0;
  d.noise_weighted = true, d.residual_terms = 100;
  const double penalty_8 = 8 * std::log(100.0);
  d.candidates.push_back(refitted(Effect::backlash, Shape::gapped_spring, 0.0096, 92.0 + penalty_8, 8));            // c = 1
  d.candidates.push_back(refitted(Effect::nonlinear_elasticity, Shape::yeoh, 0.0103, 92.0 + penalty_8 + 25.0, 7));  // 25 higher: decided
  const std::string reason = effect_reason(d, d.candidates.front(), 0.1);
  CAPTURE(reason);
  CHECK(reason.find("fits about as well") == std::string::npos);
  CHECK(reason.find("(nonlinear-elasticity) comes within 10 % of the gap with 1 parameter fewer (err (6.1) 0.0103), but its BIC is 25.0 higher, "
                    "which the data decide") != std::string::npos);
  CHECK(alike_candidates(d, d.candidates.front(), 0.1).empty());
  // 9 higher: not decided, alike.
  d.candidates[1].criterion = 92.0 + penalty_8 + 9.0;
  CHECK(alike_candidates(d, d.candidates.front(), 0.1).size() == 1);
  CHECK(effect_reason(d, d.candidates.front(), 0.1).find("which the data decide") == std::string::npos);
}

// A candidate refitted otherwise than screened (CandidateOutcome::limit_of) is named by what was
// screened, then by what was refitted; where that is the same element (fitted from the file's
// start values), it is named once.
TEST_CASE("a named effect's reason names the screened element once where it was refitted as screened, otherwise both") {
  Diagnosis d;
  d.gap_name = "RMS force residual";
  d.gap_before = 0.0386, d.criterion_before = -10000.0;
  CandidateOutcome again = refitted(Effect::rate_dependence, Shape::maxwell, 0.0052, -18000.0, 7);
  again.screened_as = trial_summary(again.screened.trial);
  again.limit_of = "fitted as the model was, from the file's start values";
  const std::string once = effect_reason(d, again, 0.1);
  CAPTURE(once);
  CHECK(once.find(again.screened_as +
                  " alone would remove 60 % of the objective and, fitted as the model was, from the file's start values, earns it") !=
        std::string::npos);
  CHECK(once.find(again.screened_as) == once.rfind(again.screened_as));
  CandidateOutcome limit = again;
  limit.screened_as = "a slider-capped fluid column (k = 50 N/mm)";
  limit.limit_of = "the limit without inertia of the fluid column before it";
  const std::string both = effect_reason(d, limit, 0.1);
  CAPTURE(both);
  CHECK(both.find("a slider-capped fluid column (k = 50 N/mm) alone would remove 60 % of the objective, and " + again.screened_as +
                  ", the limit without inertia of the fluid column before it, earns it") != std::string::npos);
}

// Where the model's BIC is at its likelihood's maximum (noise-weighted), the best candidate a
// reason names is of those whose BIC is too: a refit's BIC (eq. 5.1's fit, 12121 on a real
// amplitude sweep against the model's 1046) is only an upper bound.
TEST_CASE("the best candidate is the lowest BIC of those taken at the likelihood's maximum where the criterion is noise-weighted") {
  Diagnosis d;
  d.candidates.push_back(refitted(Effect::amplitude_dependence, Shape::friction, 0.047, 900.0, 10));  // as refitted
  d.candidates.push_back(refitted(Effect::amplitude_dependence, Shape::friction, 0.047, 1220.0, 10));
  d.candidates.back().at_likelihood_maximum = true;
  d.candidates.push_back(refitted(Effect::rate_dependence, Shape::maxwell, 0.048, 1300.0, 10));
  d.candidates.back().at_likelihood_maximum = true;
  CHECK(best_candidate(d) == &d.candidates[0]);  // not noise-weighted: the lowest BIC
  d.noise_weighted = true;
  CHECK(best_candidate(d) == &d.candidates[1]);
  d.candidates[1].at_likelihood_maximum = d.candidates[2].at_likelihood_maximum = false;
  CHECK(best_candidate(d) == &d.candidates[0]);  // none at the maximum: the lowest
}

}  // namespace evidence_text_test
