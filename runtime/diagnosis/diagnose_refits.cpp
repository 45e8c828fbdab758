// Steps 3 and 4 of rheo diagnose (diagnose.hpp): the leading candidates refitted, with the
// limits, restarts and fits from the file's start values that follow them (diagnoser.hpp).
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

Diagnoser::CandidateParameters Diagnoser::candidate_parameters(const lang::CheckedModel& candidate, const std::string& element) const {
  CandidateParameters out;
  for (const auto& path : kept_paths_)
    if (const int i = parameter_index(candidate, path); i >= 0) out.kept.push_back(i);
  for (std::size_t i = 0; i < candidate.parameters.size(); ++i) {
    const lang::Parameter& p = candidate.parameters[i];
    if (p.free && p.path.starts_with(element + ".") && std::find(out.kept.begin(), out.kept.end(), static_cast<int>(i)) == out.kept.end())
      out.added.push_back(static_cast<int>(i));
  }
  return out;
}

void Diagnoser::refit_leading(const std::vector<ScreenedEffect>& screened_effects) {
  const double leading_gain = screened_effects.empty() ? 0.0 : screened_effects.front().gain;
  int refitted = 0;
  int to_refit = 0;  // the refits to run, for their share of the time left
  int begun = 0;     // of those, begun
  // The offset is refitted whatever its screen says, beside the leading effects: its screen
  // holds the model still, while a preloaded history's static force (a yeoh's at the preload)
  // takes up most of a constant that a refit gives back (rig_preloaded_history: screened 5 %,
  // refitted to the noise), and its refit is one local search of the model's own parameters.
  auto offset = [](const ScreenedEffect& e) { return e.effect == Effect::offset; };
  for (const ScreenedEffect& screened : screened_effects)
    if (!offset(screened) && screened.gain >= std::max(s_.min_screen_gain, s_.relative_screen_gain * leading_gain)) ++to_refit;
  to_refit = std::min(to_refit, s_.confirm) + static_cast<int>(std::count_if(screened_effects.begin(), screened_effects.end(), offset));
  for (const ScreenedEffect& screened : screened_effects) {
    CandidateOutcome outcome;
    outcome.screened = screened;
    const Trial& trial = screened.trial;
    outcome.element = element_name(trial, screened.effect);
    const bool leading = refitted < s_.confirm && screened.gain >= std::max(s_.min_screen_gain, s_.relative_screen_gain * leading_gain);
    if (!(leading || offset(screened)) || stopped()) {
      d_.candidates.push_back(outcome);
      continue;
    }
    refitted += leading && !offset(screened) ? 1 : 0;
    ++begun;
    const double share = 1.0 / (to_refit - begun + 2);
    const std::size_t column_at = d_.candidates.size();
    std::optional<Trial> bulged;  // the best refitted column's, with its walls' spring
    const std::optional<Trial> limit = refit_candidate(trial, outcome, share, nullptr, &bulged);
    if (limit && !stopped()) refit_limit(screened, outcome, trial, *limit, column_at, share, bulged);
    if (screened.simpler && !stopped() && !limit) refit_simpler(screened, share);
    if (!bulged || stopped() || column_reaches_noise(column_at)) continue;
    // A column that stops short of the noise may miss the stiffness its node rests on: the
    // chamber walls' spring beside the mass and channel (candidate_model.hpp bulged_column).
    CandidateOutcome walls;
    walls.screened = screened;
    walls.screened.trial = *bulged;
    walls.element = outcome.element;
    walls.limit_of = fmt::format(
        "the fluid column with the chamber walls' spring beside its mass and channel, started from the column's optimum (err {:.4g})",
        d_.candidates[column_at].gap_after);
    refit_candidate(*bulged, walls, share);
  }
  if (capped_arm_ && !stopped()) refit_friction_limit();
}

void Diagnoser::exchange_roles(const lang::CheckedModel& model, const std::string& element, const std::vector<int>& free, double share,
                               FitResult& result) {
  if (!outlasts_sticking(model, result.network, element, data_)) return;
  for (const lang::Element& e : model.root.children) {
    if (stopped()) return;
    const std::optional<std::vector<double>> start = roles_exchanged(model, result.network, element, e);
    if (!start) continue;
    const int budget = std::max(affordable_evaluations(result.network, data_, s_, 0) / 4, kLocalJacobians * (static_cast<int>(free.size()) + 1));
    FitResult again = fit(result.network.with_parameters(*start), free, data_, local_search(within(share).fit, budget));
    const int evaluations = result.evaluations + again.evaluations;
    const bool interrupted = result.interrupted || again.interrupted, time_limited = result.time_limited || again.time_limited;
    if (again.objective < result.objective) {
      again.start_values = result.start_values;
      again.yeoh_started = result.yeoh_started;
      again.wall_seconds += result.wall_seconds;
      result = std::move(again);
    }
    result.evaluations = evaluations, result.interrupted = interrupted, result.time_limited = time_limited;
    if (interrupted) return;
  }
}

void Diagnoser::refit_friction_limit() {
  CandidateOutcome limit;
  limit.screened = capped_arm_->arm.screened;
  limit.screened.effect = Effect::amplitude_dependence;
  limit.screened.trial = capped_arm_->limit;
  limit.element = element_name(capped_arm_->limit, Effect::amplitude_dependence);
  limit.screened_as = capped_arm_->arm.screened_as.empty() ? trial_summary(capped_arm_->arm.screened.trial) : capped_arm_->arm.screened_as;
  limit.limit_of = fmt::format(
      "the limit tau -> infinity of the capped Maxwell arm refitted before it (tau = {:.4g} s, beyond the {:.3g} s the drives stick it): a "
      "friction element, one parameter fewer",
      capped_arm_->tau, capped_arm_->stick);
  refit_candidate(capped_arm_->limit, limit, 0.5);
}

void Diagnoser::refit_simpler(const ScreenedEffect& screened, double share) {
  CandidateOutcome simpler;
  simpler.screened = screened;
  simpler.screened.trial = *screened.simpler;
  simpler.element = element_name(*screened.simpler, screened.effect);
  const int fewer = added_parameter_count(screened.trial) - added_parameter_count(*screened.simpler);
  simpler.limit_of = fmt::format("with {} parameter{} fewer, screened within the parsimony margin of it ({:.0f} % alone)", fewer,
                                 fewer == 1 ? "" : "s", 100.0 * screened.simpler_gain);
  simpler.screened_as = trial_summary(screened.trial);
  refit_candidate(*screened.simpler, simpler, share);
}

void Diagnoser::refit_limit(const ScreenedEffect& screened, const CandidateOutcome& outcome, const Trial& trial, const Trial& limit,
                            std::size_t column_at, double share, std::optional<Trial>& bulged) {
  CandidateOutcome limit_outcome;
  limit_outcome.screened = screened;
  limit_outcome.screened.trial = limit;
  limit_outcome.element = outcome.element;
  limit_outcome.limit_of = fmt::format(
      "the limit without inertia of the fluid column before it (its chamber and channel as a Maxwell "
      "element, tau = c/k = {:.4g} ms){}",
      limit.time * 1e3, outcome.unresolved.empty() ? "" : ", whose resonance the data cannot place");
  const std::optional<Trial> restart = refit_candidate(limit, limit_outcome, share, &trial);
  // The column holds its limit (b -> 0): a column refit that does not end clearly below the
  // limit's gap (by more than the parsimony that would choose the limit) stopped outside
  // its basin, or found no use for its inertia, and searches again from the limit's optimum.
  const double column_gap = d_.candidates[column_at].gap_after, limit_gap = d_.candidates.back().gap_after;
  if (!restart || stopped() || !(limit_gap <= (1.0 + s_.parsimony) * column_gap)) return;
  CandidateOutcome again;
  again.screened = screened;
  again.screened.trial = *restart;
  again.element = outcome.element;
  again.limit_of = fmt::format("the fluid column again, started from its limit's optimum (its first refit stopped at {:.4g}, {} the limit's {:.4g})",
                               column_gap, limit_gap < column_gap ? "above" : "not clearly below", limit_gap);
  std::optional<Trial> bulged_again;
  refit_candidate(*restart, again, share, nullptr, &bulged_again);
  if (bulged_again && d_.candidates.back().gap_after < column_gap) bulged = bulged_again;
}

bool Diagnoser::column_reaches_noise(std::size_t column_at) const {
  const CandidateOutcome* best = &d_.candidates[column_at];
  for (std::size_t i = column_at; i < d_.candidates.size(); ++i)
    if (d_.candidates[i].screened.trial.shape == Shape::capped_column && d_.candidates[i].gap_after < best->gap_after) best = &d_.candidates[i];
  return outcome_reaches_noise(*best);
}

void Diagnoser::refit_together() {
  if (stopped()) return;
  std::optional<CandidateOutcome> both = played_and_split(d_.candidates, d_.before.network);
  if (!both) return;
  both->element = element_name(both->screened.trial, both->screened.effect);
  const Trial together = both->screened.trial;
  refit_candidate(together, *both, 1.0);
}

void Diagnoser::refit_as_written() {
  if (stopped() || !residual_beyond_noise()) return;
  std::vector<CandidateOutcome> leading;
  for (const CandidateOutcome& c : d_.candidates)
    if (c.refitted && c.screened.trial.shape != Shape::force_offset) leading.push_back(c);
  std::stable_sort(leading.begin(), leading.end(), [](const CandidateOutcome& a, const CandidateOutcome& b) { return a.gap_after < b.gap_after; });
  std::vector<Shape> shapes;
  std::erase_if(leading, [&](const CandidateOutcome& c) {
    if (std::find(shapes.begin(), shapes.end(), c.screened.trial.shape) != shapes.end()) return true;
    shapes.push_back(c.screened.trial.shape);
    return false;
  });
  if (leading.size() > static_cast<std::size_t>(s_.confirm)) leading.resize(static_cast<std::size_t>(s_.confirm));
  for (std::size_t k = 0; k < leading.size() && !stopped(); ++k) {
    const auto started = std::chrono::steady_clock::now();
    CandidateOutcome again;
    again.screened = leading[k].screened;
    again.element = leading[k].element;
    again.screened_as = leading[k].screened_as.empty() ? trial_summary(leading[k].screened.trial) : leading[k].screened_as;
    again.limit_of = fmt::format("fitted as the model was, from the file's start values (refitted from the model's fit it stopped at {:.4g})",
                                 leading[k].gap_after);
    const Trial& trial = again.screened.trial;
    stage(fmt::format("fitting with {} for {} from the file's start values", trial_summary(trial), effect_name(again.screened.effect)));
    const std::string comment = fmt::format("candidate for {}", effect_name(again.screened.effect));
    Compiled candidate = compile(source_, with_trial(source_.text, *base_.model, trial, again.element, scales_.bounds, comment));
    const auto [kept, added] = candidate_parameters(*candidate.model, again.element);
    std::vector<int> free = kept;
    free.insert(free.end(), added.begin(), added.end());
    std::sort(free.begin(), free.end());
    const double share = 1.0 / static_cast<double>(leading.size() - k + 1);
    FitSettings settings = within(share).fit;
    settings.statistics = false;
    FitResult result = fit(Network::compile(*candidate.model), free, data_, settings);
    result.network = with_gaps_in_play(result.network);
    again.unresolved = resolved_resonance(trial, *candidate.model, result.network, again.element, scales_);
    judge(trial, again, share, started, std::move(candidate), std::move(result), data_);
  }
}

std::string Diagnoser::element_name(const Trial& trial, Effect effect) const {
  if (trial.shape == Shape::gapped_element) return candidate_name(*fitted_.model, Effect::backlash);  // a block around the element
  return trial.replaces.empty() ? candidate_name(*fitted_.model, effect) : trial.replaces;
}

std::optional<Trial> Diagnoser::refit_candidate(const Trial& trial, CandidateOutcome& outcome, double share, const Trial* column,
                                                std::optional<Trial>* bulged) {
  const auto started = std::chrono::steady_clock::now();
  stage(fmt::format("refitting with {} for {}", trial_summary(trial), effect_name(outcome.screened.effect)));
  if (trial.shape == Shape::force_offset) {
    FitResult result = refit_offsets(share);
    judge(trial, outcome, share, started, base_, std::move(result), offset_data());
    return std::nullopt;
  }
  const std::string comment = fmt::format("candidate for {}", effect_name(outcome.screened.effect));
  Compiled candidate = compile(source_, with_trial(fitted_text_, *fitted_.model, trial, outcome.element, scales_.bounds, comment));
  auto [kept, added] = candidate_parameters(*candidate.model, outcome.element);
  if (trial.shape == Shape::capped_column && trial.bulge > 0.0) {
    // The column's own parameters start at its refitted optimum, kept: the global look searches
    // the walls' spring alone (over the whole column's bounds it reaches undamped corners whose
    // periodic state does not settle, time-stepped at seconds a point).
    const int walls = parameter_index(*candidate.model, outcome.element + ".column.bulge.k");
    for (int i : added)
      if (i != walls) kept.push_back(i);
    added.assign(1, walls);
  }
  FitResult result = staged_refit(Network::compile(*candidate.model), kept, added, data_, within(share));
  if (trial.shape == Shape::capped_maxwell && !result.interrupted) {
    std::vector<int> free = kept;
    free.insert(free.end(), added.begin(), added.end());
    std::sort(free.begin(), free.end());
    exchange_roles(*candidate.model, outcome.element, free, share, result);
  }
  result.network = with_gaps_in_play(result.network);  // the same predictions, as a file can state them
  outcome.unresolved = resolved_resonance(trial, *candidate.model, result.network, outcome.element, scales_);
  std::optional<Trial> next;
  if (trial.shape == Shape::capped_column && trial.bulge == 0.0)
    next = resonance_free_limit(trial, *candidate.model, result.network, outcome.element);
  if (trial.shape == Shape::capped_column && trial.bulge == 0.0 && bulged != nullptr)
    *bulged = bulged_column(trial, *candidate.model, result.network, outcome.element);
  if (column != nullptr) next = column_from_limit(*column, *candidate.model, result.network, outcome.element);
  if (trial.shape == Shape::capped_maxwell) {
    CappedArm arm{outcome, friction_limit(trial, *candidate.model, result.network, outcome.element), fit_gap(result),
                  result.network.parameter(parameter_index(*candidate.model, outcome.element + ".arm.tau")), 0.0};
    arm.stick = longest_stick(data_, arm.limit.slip);  // for the reason
    if (outlasts_sticking(*candidate.model, result.network, outcome.element, data_) && (!capped_arm_ || arm.gap < capped_arm_->gap))
      capped_arm_ = std::move(arm);
  }
  judge(trial, outcome, share, started, std::move(candidate), std::move(result), data_);
  return next;
}

}  // namespace rheo::runtime::diagnosis
