// Step 4 of rheo diagnose (diagnose.hpp): a refitted candidate judged against the model and the
// choice so far (diagnoser.hpp).
#include "runtime/diagnosis/diagnoser.hpp"

#include "lang/fitted_source.hpp"
#include "lang/source_edit.hpp"
#include "runtime/diagnosis/candidate_model.hpp"
#include "runtime/diagnosis/evidence_text.hpp"
#include "runtime/diagnosis/refit.hpp"
#include "runtime/diagnosis/together.hpp"
#include "runtime/fit/fit_scoring.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace rheo::runtime::diagnosis {

bool Diagnoser::outcome_reaches_noise(const CandidateOutcome& outcome) const {
  return reaches_noise(before_residual(), {outcome.gap_after, outcome.criterion - penalty(outcome), outcome.parameters}, d_.noise,
                       d_.residual_terms, d_.noise_weighted);
}

bool Diagnoser::residual_beyond_noise() const {
  return d_.noise.estimated && beyond_noise_ratio(residual_ratio(before_residual(), d_.noise, d_.residual_terms, d_.noise_weighted), d_.noise);
}

void Diagnoser::judge(const Trial& trial, CandidateOutcome& outcome, double share, std::chrono::steady_clock::time_point started,
                      Compiled candidate, FitResult result, const std::vector<FitDataSet>& data) {
  outcome.refitted = true;
  outcome.gap_after = fit_gap(result);
  outcome.criterion = criterion(result, d_.residual_terms, d_.noise_weighted, d_.noise);
  outcome.parameters = fitted_parameters(result);
  if (trial.shape != Shape::force_offset) outcome.fitted = added_summary(result, outcome.element);
  outcome.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  d_.interrupted = d_.interrupted || result.interrupted;
  d_.time_limited = d_.time_limited || result.time_limited;
  // The residual falls by min_improvement (criterion.hpp lowers_residual: the gap, or where
  // weighted the residual over the noise); a gap just beyond the noise cannot, and taking it
  // to the noise earns too, judged as the verdict is (criterion.hpp reaches_noise).
  auto drops = [&] {
    return lowers_residual(before_residual(), {outcome.gap_after, outcome.criterion - penalty(outcome), outcome.parameters}, s_.min_improvement,
                           d_.residual_terms, d_.noise_weighted);
  };
  bool gains = outcome.unresolved.empty() && (drops() || outcome_reaches_noise(outcome));
  // A candidate that may earn is judged, as the model was, at its likelihood's maximum; one
  // whose fit earns already keeps its fit's chi^2, an upper bound of its least.
  if (gains && d_.noise_weighted && !(outcome.criterion < d_.criterion_before) && !stopped()) {
    at_likelihood_maximum(outcome, result, data, share);
    gains = drops() || outcome_reaches_noise(outcome);
  }
  const bool earns = gains && outcome.criterion < d_.criterion_before;
  if (earns && (!chosen_ || preferred_to_choice(outcome, result, data, share)))
    chosen_ = Chosen{d_.candidates.size(), trial, std::move(candidate), std::move(result), &data};
  else if (d_.noise_weighted && !outcome.at_likelihood_maximum && (!closest_ || outcome.gap_after < d_.candidates[closest_->candidate].gap_after))
    closest_ = Chosen{d_.candidates.size(), trial, std::move(candidate), std::move(result), &data};
  d_.candidates.push_back(outcome);
}

void Diagnoser::at_likelihood_maximum(CandidateOutcome& outcome, const FitResult& result, const std::vector<FitDataSet>& data, double share) {
  const int evaluations = kLikelihoodJacobians * (outcome.parameters + 1);
  outcome.criterion = least_chi_square(result, data, d_.noise, within(share).fit, evaluations).chi_square + penalty(outcome);
  outcome.at_likelihood_maximum = true;
}

bool Diagnoser::preferred_to_choice(CandidateOutcome& outcome, const FitResult& result, const std::vector<FitDataSet>& data, double share) {
  CandidateOutcome& choice = d_.candidates[chosen_->candidate];
  auto both_at_maximum = [&] {
    if (!d_.noise_weighted || stopped()) return;
    if (!outcome.at_likelihood_maximum) at_likelihood_maximum(outcome, result, data, share);
    if (!choice.at_likelihood_maximum) at_likelihood_maximum(choice, chosen_->result, *chosen_->data, share);
  };
  const bool outcome_simpler = outcome.parameters < choice.parameters;
  CandidateOutcome& simpler = outcome_simpler ? outcome : choice;
  CandidateOutcome& richer = outcome_simpler ? choice : outcome;
  const bool within_margin = simpler.gap_after <= (1.0 + s_.parsimony) * richer.gap_after;
  if (outcome.parameters == choice.parameters || (!d_.noise_weighted && !within_margin)) {
    both_at_maximum();
    return outcome.criterion < choice.criterion;
  }
  if (!within_margin) {
    // The simpler's least first: where the richer's BIC as refitted (at or above its least, its
    // overdispersion too) is positively lower already, its least is not needed.
    if (!stopped() && !simpler.at_likelihood_maximum)
      at_likelihood_maximum(simpler, outcome_simpler ? result : chosen_->result, outcome_simpler ? data : *chosen_->data, share);
    if (!positively_lower(richer.criterion, simpler.criterion, richer.parameters, d_.residual_terms)) both_at_maximum();
    return positively_lower(richer.criterion, simpler.criterion, richer.parameters, d_.residual_terms) != outcome_simpler;
  }
  if (!d_.noise_weighted || stopped()) return outcome_simpler;
  // The richer's least first: where it is not decisively lower than the simpler's BIC as
  // refitted (at or above its least), it is not at the maximum either.
  if (!richer.at_likelihood_maximum)
    at_likelihood_maximum(richer, outcome_simpler ? chosen_->result : result, outcome_simpler ? *chosen_->data : data, share);
  if (decisively_lower(richer.criterion, simpler.criterion, richer.parameters, d_.residual_terms)) both_at_maximum();
  return decisively_lower(richer.criterion, simpler.criterion, richer.parameters, d_.residual_terms) != outcome_simpler;
}

const std::vector<FitDataSet>& Diagnoser::offset_data() {
  if (!offset_data_) offset_data_ = with_free_offsets(data_, fixed_offsets(data_));
  return *offset_data_;
}

}  // namespace rheo::runtime::diagnosis
