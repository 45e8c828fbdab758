#include "runtime/diagnosis/diagnose.hpp"

#include "lang/fitted_source.hpp"
#include "lang/frontend.hpp"
#include "lang/source_edit.hpp"
#include "runtime/diagnosis/candidate_model.hpp"
#include "runtime/diagnosis/criterion.hpp"
#include "runtime/diagnosis/evidence_text.hpp"
#include "runtime/diagnosis/offset_candidate.hpp"
#include "runtime/diagnosis/refit.hpp"
#include "runtime/diagnosis/together.hpp"
#include "runtime/fit/fit_scoring.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <stdexcept>

namespace rheo::runtime::diagnosis {
namespace {

struct Compiled {
  std::shared_ptr<const lang::Program> program;  // owns the model a Network refers to
  const lang::CheckedModel* model = nullptr;
};

Compiled compile(const ModelSource& source, const std::string& text) {
  auto program = std::make_shared<const lang::Program>(lang::compile_source(source.file, text));
  const lang::CheckedModel* model = program->find_model(source.model);
  if (!model) throw std::logic_error(fmt::format("{} has no model '{}'", source.file, source.model));
  return {program, model};
}

struct Chosen {
  std::size_t candidate = 0;
  Trial trial;
  Compiled compiled;  // owns the model result.network refers to
  FitResult result;
  const std::vector<FitDataSet>* data = nullptr;  // as refitted: the offset candidate's frees force offsets
};

}  // namespace

double fit_gap(const FitResult& result) {
  if (result.err > 0.0) return result.err;
  double sum = 0.0;
  int histories = 0;
  for (const auto& set : result.datasets)
    if (!set.harmonic) sum += set.err * set.err, ++histories;
  return histories ? std::sqrt(sum / histories) : result.err;
}

namespace {

// One diagnosis, its steps as methods in the order of diagnose.hpp: fit the model (1), screen the
// effects (2), refit the leading ones and keep the one that earns (3, 4), polish it (5), and write
// the refined source.
class Diagnoser {
 public:
  Diagnoser(const ModelSource& source, const std::vector<FitDataSet>& data, const DiagnoseSettings& settings)
      : source_(source), data_(data), settings_(settings), s_(settings), base_(compile(source, source.text)) {
    s_.fit.score.method = FitMethod::exact;
    s_.fit.statistics = settings.standard_errors;
    s_.fit.score.harmonic.solver = diagnosis_solver(settings.fit.score.harmonic.solver, data);
  }

  Diagnosis run() {
    fit_model();
    refit_leading(screen_effects());
    if (!chosen_) refit_together();
    if (!chosen_) refit_as_written();
    if (!chosen_) return finish_none();
    polish();
    return finish_refined();
  }

 private:
  void stage(const std::string& what) const {
    if (s_.stage) s_.stage(what);
  }

  // Seconds to the deadline; +inf without one.
  double time_left() const {
    if (!s_.deadline) return std::numeric_limits<double>::infinity();
    return std::chrono::duration<double>(*s_.deadline - std::chrono::steady_clock::now()).count();
  }

  // Whether the next step must not begin: a fit was interrupted, or the deadline has passed.
  bool stopped() {
    if (!d_.interrupted && time_left() <= 0.0) d_.time_limited = true;
    return d_.interrupted || d_.time_limited;
  }

  // S with its fits bounded by SHARE of the time left (and by their own limit).
  DiagnoseSettings within(double share) const {
    DiagnoseSettings s = s_;
    if (const double left = time_left(); std::isfinite(left))
      s.fit.time_limit = std::min(s.fit.time_limit.value_or(1e300), std::max(1e-3, share * left));
    return s;
  }

  std::vector<int> free_parameters() const {
    if (settings_.free.empty()) return lang::default_free_parameters(*base_.model);
    std::vector<int> free;
    for (const auto& path : settings_.free) free.push_back(parameter_index(*base_.model, path));
    if (std::count(free.begin(), free.end(), -1)) throw std::logic_error(fmt::format("model '{}': a free parameter is not in it", source_.model));
    return free;
  }

  // Step 1: the model as given, fitted; its residual patterns and its fitted source.
  void fit_model() {
    const std::vector<int> free = free_parameters();
    const bool harmonic = std::any_of(data_.begin(), data_.end(), [](const FitDataSet& set) { return set.is_harmonic(); });
    d_.gap_name = harmonic ? "err (6.1)" : "RMS force residual";
    stage(fmt::format("fitting model {}", source_.model));
    d_.before_program = base_.program;
    d_.before = fit(Network::compile(*base_.model), free, data_, within(1.0 / 3.0).fit);
    d_.before.network = with_gaps_in_play(d_.before.network);  // the same predictions, as the fitted source can state them
    d_.time_limited = d_.before.time_limited;
    d_.gap_before = d_.gap_after = fit_gap(d_.before);
    d_.residual_terms = residual_terms(data_);
    d_.patterns = residual_patterns(d_.before, data_);
    d_.noise = estimate_noise(d_.before, data_);
    d_.noise_weighted = noise_weighted(data_, d_.noise);
    const int p = fitted_parameters(d_.before);
    d_.criterion_before = criterion(d_.before, d_.residual_terms, d_.noise_weighted, d_.noise);
    d_.noise_ratio = noise_ratio(d_.gap_before, d_.noise, d_.residual_terms, p);
    if (d_.noise_weighted && !stopped()) {
      // The likelihood at its maximum (criterion.hpp least_chi_square), from the fit and from its start.
      stage("weighing the fit by the noise");
      // The noise estimated again where the likelihood is at its maximum (criterion.hpp noise_at_likelihood_maximum).
      const NoiseAndChiSquare weighed = noise_at_likelihood_maximum(d_.before, data_, d_.noise, within(1.0 / 3.0).fit,
                                                                    2 * kLikelihoodJacobians * (p + 1));
      d_.noise = weighed.noise;
      d_.chi_square_before = weighed.chi_square;
      d_.criterion_before = d_.chi_square_before + p * std::log(static_cast<double>(d_.residual_terms));
      d_.chi_square_ratio = chi_square_ratio(d_.chi_square_before, d_.residual_terms, p);
      d_.noise_ratio = noise_ratio(d_.gap_before, d_.noise, d_.residual_terms, p);
    }
    fitted_text_ = lang::write_fitted_source(source_.text, source_.file, *base_.model, d_.before.network.parameters(), d_.before.free, {});
    d_.interrupted = d_.before.interrupted;
    for (int i : d_.before.free) kept_paths_.push_back(base_.model->parameters[static_cast<std::size_t>(i)].path);
    fitted_ = compile(source_, fitted_text_);
    scales_ = data_scales(data_);
  }

  // Step 2: every effect screened, leading first.
  std::vector<ScreenedEffect> screen_effects() {
    if (stopped()) return {};
    stage("screening the effects");
    std::vector<ScreenedEffect> screened = screen(d_.before, data_, s_.fit.score, s_.parsimony);
    // Harmonic sweeps that measure no interaction (patterns.hpp) give no evidence of coupling,
    // and a coupled element that fits them would be named for what they cannot show.
    const bool histories = std::any_of(data_.begin(), data_.end(), [](const FitDataSet& set) { return !set.is_harmonic(); });
    if (d_.patterns.has_harmonic && !histories && !d_.patterns.harmonic.interaction_measured())
      std::erase_if(screened, [](const ScreenedEffect& e) { return e.effect == Effect::coupled_amplitude_frequency; });
    return screened;
  }

  // Step 3: the leading effects refitted (a refitted capped fluid column is followed by its limit
  // without inertia, and where it stops short of the noise by itself with its walls' spring);
  // the others recorded as screened only.
  void refit_leading(const std::vector<ScreenedEffect>& screened_effects) {
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

  // Of the refitted slider-capped Maxwell arms whose tau exceeds the longest the drives stick them
  // (candidate_model.hpp longest_stick), the one of the lowest gap, refitted as its limit tau ->
  // infinity, a friction element (candidate_model.hpp friction_limit): where the data cannot tell
  // the two apart, the friction element wins by parsimony. (Friction hidden in slow triangles was
  // named coupled: arms refitted to tau = 2.4e5 s and 8.4 s, sticking for at most 0.7 s, the
  // friction element itself screened fourth, 36.3 % against 36.4 %, and not refitted.)
  void refit_friction_limit() {
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

  // The screen's simpler member of the effect, which screened within the parsimony margin of its
  // best (screen.hpp ScreenedEffect::simpler), refitted beside it. (A capped fluid column's
  // simpler member, the capped Maxwell element, is its limit without inertia, refitted anyway.)
  void refit_simpler(const ScreenedEffect& screened, double share) {
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

  // The column's limit without inertia competes with it: where the data hold no resonance (or
  // cannot place it) the limit earns the coupling with one parameter fewer. Where the column
  // stops above its limit, it is searched again from the limit's optimum; BULGED becomes that
  // search's walls' start where it ends lower than the column at COLUMN_AT.
  void refit_limit(const ScreenedEffect& screened, const CandidateOutcome& outcome, const Trial& trial, const Trial& limit, std::size_t column_at,
                   double share, std::optional<Trial>& bulged) {
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

  // Whether the column refitted at COLUMN_AT (or the search again after it, the last candidate
  // where that ended lower) leaves no more than the noise, as judge() counts reaching it.
  bool column_reaches_noise(std::size_t column_at) const {
    const CandidateOutcome* best = &d_.candidates[column_at];
    for (std::size_t i = column_at; i < d_.candidates.size(); ++i)
      if (d_.candidates[i].screened.trial.shape == Shape::capped_column && d_.candidates[i].gap_after < best->gap_after) best = &d_.candidates[i];
    return outcome_reaches_noise(*best);
  }

  // BIC's parameter penalty p ln N of OUTCOME, and whether OUTCOME (its criterion less that
  // penalty the chi^2) reaches the noise as the verdict judges it (criterion.hpp reaches_noise).
  double penalty(const CandidateOutcome& outcome) const { return outcome.parameters * std::log(static_cast<double>(d_.residual_terms)); }
  bool outcome_reaches_noise(const CandidateOutcome& outcome) const {
    return reaches_noise(before_residual(), {outcome.gap_after, outcome.criterion - penalty(outcome), outcome.parameters}, d_.noise,
                         d_.residual_terms, d_.noise_weighted);
  }

  // Step 4 again where no candidate earned alone but both free play and asymmetry were
  // refitted: free play in front of a friction element whose yield is made one-sided, refitted
  // together (a friction branch behind play with unequal caps: each alone leaves the other's
  // residual). The element: the one the asymmetry was found in, else the root friction
  // element with the largest cap; the play's width and centre start from the best refitted
  // play, the split from the best refitted asymmetry (0.2 where it had none). Named by the
  // effect that did better alone.
  void refit_together() {
    if (stopped()) return;
    std::optional<CandidateOutcome> both = played_and_split(d_.candidates, d_.before.network);
    if (!both) return;
    both->element = element_name(both->screened.trial, both->screened.effect);
    const Trial together = both->screened.trial;
    refit_candidate(together, *both, 1.0);
  }

  // Step 4 once more where no candidate earned and the residual is beyond the noise: the
  // leading refitted shapes (one per shape, lowest gap first, at most `confirm`) fitted as the
  // model was in step 1, every free parameter by rheo fit's strategy from the file's start
  // values with the element as screened, not from the model's fit: that fit may have taken the
  // missing effect into the model's own elements (a Maxwell element's tau at 132 ms for 7 ms, a
  // friction element's k at 950 N/mm for 114, where a capped Maxwell arm was missing), which no
  // local search from it gives back.
  void refit_as_written() {
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
      std::vector<int> free;
      for (std::size_t i = 0; i < candidate.model->parameters.size(); ++i) {
        const lang::Parameter& p = candidate.model->parameters[i];
        if (std::find(kept_paths_.begin(), kept_paths_.end(), p.path) != kept_paths_.end() || (p.free && p.path.starts_with(again.element + ".")))
          free.push_back(static_cast<int>(i));
      }
      const double share = 1.0 / static_cast<double>(leading.size() - k + 1);
      FitSettings settings = within(share).fit;
      settings.statistics = false;
      FitResult result = fit(Network::compile(*candidate.model), free, data_, settings);
      result.network = with_gaps_in_play(result.network);
      again.unresolved = resolved_resonance(trial, *candidate.model, result.network, again.element, scales_);
      judge(trial, again, share, started, std::move(candidate), std::move(result), data_);
    }
  }

  // Whether the model's residual as fitted is beyond the estimated noise (unexplained, not none).
  bool residual_beyond_noise() const {
    return d_.noise.estimated && beyond_noise_ratio(residual_ratio(before_residual(), d_.noise, d_.residual_terms, d_.noise_weighted), d_.noise);
  }

  // The name of TRIAL's element in the candidate model: a new root name (`backlash` for the
  // block that puts play in front of an element, also when refitted together with its
  // one-sided yield), or the element it replaces in place (a yeoh or poly_spring for a spring,
  // a friction element made one-sided).
  std::string element_name(const Trial& trial, Effect effect) const {
    if (trial.shape == Shape::gapped_element) return candidate_name(*fitted_.model, Effect::backlash);  // a block around the element
    return trial.replaces.empty() ? candidate_name(*fitted_.model, effect) : trial.replaces;
  }

  // Steps 3 and 4 for one candidate: the fitted model with TRIAL added as OUTCOME.element,
  // refitted in two stages; recorded, and kept as the choice if it earns its parameters and is
  // preferred to the choice so far. Returns the limit without inertia of a capped fluid column,
  // and for the limit of COLUMN (given) that column started from the limit's optimum.
  // SHARE: of the time left, for this refit.
  // BULGED, where given, receives a refitted capped column's start with its walls' spring.
  std::optional<Trial> refit_candidate(const Trial& trial, CandidateOutcome& outcome, double share, const Trial* column = nullptr,
                                       std::optional<Trial>* bulged = nullptr) {
    const auto started = std::chrono::steady_clock::now();
    stage(fmt::format("refitting with {} for {}", trial_summary(trial), effect_name(outcome.screened.effect)));
    if (trial.shape == Shape::force_offset) {
      FitResult result = refit_offsets(share);
      judge(trial, outcome, share, started, base_, std::move(result), offset_data());
      return std::nullopt;
    }
    const std::string comment = fmt::format("candidate for {}", effect_name(outcome.screened.effect));
    Compiled candidate = compile(source_, with_trial(fitted_text_, *fitted_.model, trial, outcome.element, scales_.bounds, comment));
    std::vector<int> kept, added;
    for (const auto& path : kept_paths_)
      if (const int i = parameter_index(*candidate.model, path); i >= 0) kept.push_back(i);
    for (std::size_t i = 0; i < candidate.model->parameters.size(); ++i) {
      const lang::Parameter& p = candidate.model->parameters[i];
      if (p.free && p.path.starts_with(outcome.element + ".") && std::find(kept.begin(), kept.end(), static_cast<int>(i)) == kept.end())
        added.push_back(static_cast<int>(i));
    }
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
      arm.stick = longest_stick(data_, arm.limit.slip);
      if (arm.tau > arm.stick && (!capped_arm_ || arm.gap < capped_arm_->gap)) capped_arm_ = std::move(arm);
    }
    judge(trial, outcome, share, started, std::move(candidate), std::move(result), data_);
    return next;
  }

  // Step 4 for a refitted candidate (RESULT, refitted to DATA, of the model CANDIDATE owns):
  // recorded in OUTCOME, and kept as the choice if it earns its parameters and is preferred to
  // the choice so far.
  void judge(const Trial& trial, CandidateOutcome& outcome, double share, std::chrono::steady_clock::time_point started, Compiled candidate,
             FitResult result, const std::vector<FitDataSet>& data) {
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
    d_.candidates.push_back(outcome);
  }

  // OUTCOME's criterion at its likelihood's maximum, searched from its fit RESULT to DATA.
  void at_likelihood_maximum(CandidateOutcome& outcome, const FitResult& result, const std::vector<FitDataSet>& data, double share) {
    const int evaluations = kLikelihoodJacobians * (outcome.parameters + 1);
    outcome.criterion = least_chi_square(result, data, d_.noise, within(share).fit, evaluations).chi_square + penalty(outcome);
    outcome.at_likelihood_maximum = true;
  }

  // Whether OUTCOME (its fit RESULT to DATA), which earns, is preferred to the choice so far: the
  // one with fewer parameters when its gap is within `parsimony` of the other's (the coupled
  // shapes hold friction and Maxwell elements as limits, so they always fit at least as well),
  // unless the other's BIC is decisively lower (criterion.hpp decisively_lower: free play that
  // engages at the largest amplitudes fits within the margin of a stiffening yeoh spring's gap
  // with a chi^2 half of the spring's); else the lower BIC. Where the criterion is weighted by
  // the noise, BICs are compared with both at their likelihood's maximum, as the model's own is
  // (criterion_before): eq. 5.1's damping terms at phases near the phase noise can leave one
  // refit's chi^2 far above its least and not another's (a friction element's refit at 307, a
  // capped Maxwell arm's at 120; their least 100 and 99, one parameter apart); and of two
  // whose gaps lie beyond the margin the richer wins only where its BIC is positively lower
  // (criterion.hpp positively_lower), else the simpler.
  bool preferred_to_choice(CandidateOutcome& outcome, const FitResult& result, const std::vector<FitDataSet>& data, double share) {
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

  // The data with the force offsets the offset candidate frees (offset_candidate.hpp).
  const std::vector<FitDataSet>& offset_data() {
    if (!offset_data_) offset_data_ = with_free_offsets(data_, fixed_offsets(data_));
    return *offset_data_;
  }

  FitResult refit_offsets(double share) { return refit_with_offsets(d_.before, offset_data(), within(share)); }

  // The model's residual as fitted, its chi^2 the least (criterion.hpp Residual).
  Residual before_residual() const { return {d_.gap_before, d_.chi_square_before, fitted_parameters(d_.before)}; }

  // Step 5: Levenberg-Marquardt over every free parameter of the chosen model again (refit.hpp
  // local_search), kept when no worse; its
  // gaps' centres written within their play (candidate_model.hpp with_gaps_in_play).
  void polish() {
    if (stopped()) return;
    stage("polishing the refined model");
    const int n = static_cast<int>(chosen_->result.free.size());
    const std::vector<FitDataSet>& data = *chosen_->data;
    FitSettings settings = local_search(within(1.0).fit, affordable_evaluations(chosen_->result.network, data, s_, kLocalJacobians * (n + 1)));
    settings.statistics = settings_.standard_errors;
    settings.search.crawl_tolerance = kPolishCrawl;
    FitResult polished = fit(chosen_->result.network, chosen_->result.free, data, settings);
    d_.interrupted = polished.interrupted;
    d_.time_limited = d_.time_limited || polished.time_limited;
    polished.network = with_gaps_in_play(polished.network);
    if (polished.objective <= chosen_->result.objective) {
      polished.start_values = chosen_->result.start_values;
      polished.yeoh_started = chosen_->result.yeoh_started;
      polished.evaluations += chosen_->result.evaluations;
      polished.wall_seconds += chosen_->result.wall_seconds;
      chosen_->result = std::move(polished);
    }
  }

  // No candidate earned: the model as fitted, its residual at the noise (none) or not (unexplained).
  Diagnosis finish_none() {
    d_.effect = Effect::none;
    const bool beyond_noise = residual_beyond_noise();
    d_.verdict = beyond_noise ? Verdict::unexplained : Verdict::none;
    if (beyond_noise) d_.unexplained = residual_shape(d_.before, data_);
    d_.reason = beyond_noise ? unexplained_reason(d_) : none_reason(d_, s_);
    const std::string noise = d_.noise.estimated ? fmt::format(" (the noise leaves {:.4g})", d_.noise.floor) : "";
    std::vector<std::string> header{fmt::format("Checked by `rheo diagnose`: {}, nothing added. {} = {:.4g}{}.",
                                                beyond_noise ? "unexplained: a systematic residual no candidate removes" : "effect none",
                                                d_.gap_name, d_.gap_before, noise)};
    d_.refined_text = lang::write_fitted_source(source_.text, source_.file, *base_.model, d_.before.network.parameters(), d_.before.free, header);
    return std::move(d_);
  }

  // The chosen candidate: the refined source (the same structure as the refitted candidate,
  // under the comment that says why) with its fitted values.
  Diagnosis finish_refined() {
    d_.candidates[chosen_->candidate].chosen = true;
    d_.verdict = Verdict::named;
    const CandidateOutcome& winner = d_.candidates[chosen_->candidate];
    d_.effect = winner.screened.effect;
    d_.gap_after = fit_gap(chosen_->result);
    d_.added_element = winner.element;
    d_.reason = effect_reason(d_, winner, s_.parsimony);
    for (const CandidateOutcome* alike : alike_candidates(d_, winner, s_.parsimony)) d_.alike.push_back(alike->screened.effect);
    if (chosen_->trial.shape == Shape::force_offset) return finish_offset();
    const std::string comment = fmt::format("added by rheo diagnose: {}; {} {:.4g} -> {:.4g}", effect_name(d_.effect), d_.gap_name, d_.gap_before,
                                            d_.gap_after);
    const std::string structure = with_trial(fitted_text_, *fitted_.model, chosen_->trial, winner.element, scales_.bounds, comment);
    const Compiled refined = compile(source_, structure);
    std::vector<std::string> header{fmt::format("Refined by `rheo diagnose`: effect {}; added '{}'; {} {:.4g} -> {:.4g}.", effect_name(d_.effect),
                                                winner.element, d_.gap_name, d_.gap_before, d_.gap_after)};
    d_.refined_text = lang::write_fitted_source(structure, source_.file, *refined.model, chosen_->result.network.parameters(), chosen_->result.free,
                                                header);
    d_.added_summary = added_summary(chosen_->result, winner.element);
    d_.added_statement = statement_lines(d_.refined_text, source_, winner.element);
    d_.after = std::move(chosen_->result);
    d_.after_program = chosen_->compiled.program;
    return std::move(d_);
  }

  // finish_refined for the offset candidate: the model's structure kept, `force_offset = free`
  // written on the data lines of the histories whose offset it fits (or, for data given
  // otherwise, the --data option that says so).
  Diagnosis finish_offset() {
    d_.freed_offsets = fixed_offsets(data_);
    const std::vector<lang::FitData> lines = fit_block_lines(*base_.program, source_.fit_block, data_.size());
    const OffsetText text = offset_text(source_.text, source_.file, lines, d_.freed_offsets, chosen_->result);
    d_.added_element = "force_offset";
    d_.added_summary = text.summary;
    d_.added_statement = text.statement;
    const std::vector<std::string> header = offset_header(text, d_.freed_offsets.size(), d_.gap_name, d_.gap_before, d_.gap_after);
    d_.refined_text = lang::write_fitted_source(source_.text, source_.file, *base_.model, chosen_->result.network.parameters(),
                                                chosen_->result.free, header, text.edits);
    d_.after = std::move(chosen_->result);
    d_.after_program = chosen_->compiled.program;
    return std::move(d_);
  }

  const ModelSource& source_;
  const std::vector<FitDataSet>& data_;
  const DiagnoseSettings& settings_;
  DiagnoseSettings s_;  // settings_ with the method exact and the statistics asked for
  const Compiled base_;
  Diagnosis d_;
  std::string fitted_text_;              // the source with the values of step 1
  Compiled fitted_;                      // fitted_text_ compiled
  std::vector<std::string> kept_paths_;  // the free parameters of step 1, by path
  DataScales scales_;
  std::optional<Chosen> chosen_;
  std::optional<std::vector<FitDataSet>> offset_data_;  // offset_data()
  // The refitted slider-capped Maxwell arm slower than its sticking of the lowest gap, and its friction limit (refit_friction_limit).
  struct CappedArm {
    CandidateOutcome arm;
    Trial limit;
    double gap = 0.0;
    double tau = 0.0;    // [s]
    double stick = 0.0;  // [s]: candidate_model.hpp longest_stick at the arm's fy/k
  };
  std::optional<CappedArm> capped_arm_;
};

}  // namespace

std::string_view verdict_name(const Diagnosis& diagnosis) {
  return diagnosis.verdict == Verdict::unexplained ? "unexplained" : effect_name(diagnosis.effect);
}

SolverChoice diagnosis_solver(SolverChoice asked, const std::vector<FitDataSet>& data) {
  const bool histories = std::any_of(data.begin(), data.end(), [](const FitDataSet& set) { return !set.is_harmonic(); });
  return histories && asked == SolverChoice::automatic ? SolverChoice::fixed : asked;
}

Diagnosis diagnose(const ModelSource& source, const std::vector<FitDataSet>& data, const DiagnoseSettings& settings) {
  return Diagnoser(source, data, settings).run();
}

}  // namespace rheo::runtime::diagnosis
