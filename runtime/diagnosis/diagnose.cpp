#include "runtime/diagnosis/diagnose.hpp"

#include "lang/fitted_source.hpp"
#include "lang/frontend.hpp"
#include "lang/source_edit.hpp"
#include "runtime/diagnosis/evidence_text.hpp"
#include "runtime/fit/fit_scoring.hpp"
#include "runtime/protocols/solver_choice.hpp"
#include "runtime/stepping/tree_solver.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numbers>
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

int index_of(const lang::CheckedModel& model, const std::string& path) {
  for (std::size_t i = 0; i < model.parameters.size(); ++i)
    if (model.parameters[i].path == path) return static_cast<int>(i);
  return -1;
}

int residual_terms(const std::vector<FitDataSet>& data) {
  int n = 0;
  for (const auto& set : data) n += set.is_harmonic() ? 2 * static_cast<int>(set.harmonic().size()) : static_cast<int>(set.history().force.size());
  return n;
}

double criterion(const FitResult& r, int n) {
  return n * std::log(std::max(r.objective, 1e-300)) + static_cast<double>(r.free.size()) * std::log(static_cast<double>(n));
}

std::string element_word(Effect effect) {
  switch (effect) {
    case Effect::amplitude_dependence: return "slip";
    case Effect::rate_dependence: return "relaxation";
    case Effect::nonlinear_elasticity: return "nonlinear";
    case Effect::coupled_amplitude_frequency: return "coupled";
    case Effect::inertia: return "resonance";
    case Effect::none: break;
  }
  return "added";
}

std::string unique_name(const lang::CheckedModel& model, const std::string& word) {
  auto taken = [&](const std::string& name) {
    return std::any_of(model.root.children.begin(), model.root.children.end(), [&](const lang::Element& e) { return e.name == name; }) ||
           std::any_of(model.parameters.begin(), model.parameters.end(), [&](const lang::Parameter& p) { return p.path == name; });
  };
  std::string name = word;
  for (int k = 2; taken(name); ++k) name = fmt::format("{}{}", word, k);
  return name;
}

// The fitted model's source with TRIAL written in as NAME, under COMMENT.
std::string with_trial(const std::string& fitted_text, const lang::CheckedModel& fitted, const Trial& trial, const std::string& name,
                       const BoundScales& bounds, const std::string& comment) {
  const std::vector<std::string> lines = trial_statement(trial, name, bounds);
  if (trial.replaces.empty()) {
    std::vector<std::string> block{"# " + comment};
    block.insert(block.end(), lines.begin(), lines.end());
    return lang::append_to_model(fitted_text, fitted, block);
  }
  for (const auto& e : fitted.root.children)
    if (e.name == trial.replaces) {
      const lang::TextSpan span = lang::element_statement(fitted_text, e);
      return lang::replace_span(fitted_text, span, "# " + comment + "\n" + lang::line_indent(fitted_text, span.begin) + lines.front());
    }
  throw std::logic_error(fmt::format("model '{}' has no root element '{}' to replace", fitted.name, trial.replaces));
}

// Work of one evaluation of NETWORK in fixed time steps of a nested network, counted on one
// prediction: a time-stepped harmonic point costs the cycles it took to its periodic state
// times the steps per cycle, a history sample one step, and a closed-form point 10. A step
// under IDA (whose steps solve a DAE with Newton iterations) counts 10. A step of a network
// whose elements all sit in the root parallel block counts 0.05 (its kernel is one update per
// element, ~20 ns a step), of one whose subtrees step without iteration (linear and
// capped-linear chains, tree_solver.hpp) 0.3 (~0.13 us), of others 1 (the nested Newton
// iterations, 0.3-3 us; docs/performance.md). Counted, not timed, so that budgets, and
// results, do not depend on the machine.
double evaluation_work(const Network& network, const std::vector<FitDataSet>& data, const HarmonicOptions& options) {
  const Topology& t = network.topology();
  const double step_cost = uses_sundials(network, options.solver) ? 10.0
                           : t.subtrees.empty()                   ? 0.05
                           : steps_without_iteration(t)           ? 0.3
                                                                  : 1.0;
  double work = 0.0;
  for (const auto& set : data) {
    if (!set.is_harmonic()) {
      work += step_cost * static_cast<double>(set.history().force.size());
      continue;
    }
    for (const HarmonicPoint& point : predict(network, set, FitMethod::exact, options, nullptr).points)
      work += point.cycles == 0 ? 10.0 : step_cost * point.cycles * options.steps_per_cycle;
  }
  return work;
}

// Evaluations REFIT_WORK affords at the work per evaluation of NETWORK, within [floor, max_evaluations].
int affordable_evaluations(const Network& network, const std::vector<FitDataSet>& data, const DiagnoseSettings& s, int floor) {
  const double per_evaluation = std::max(1.0, evaluation_work(network, data, s.fit.score.harmonic));
  return static_cast<int>(std::clamp(s.refit_work / per_evaluation, static_cast<double>(floor), static_cast<double>(s.max_evaluations)));
}

FitSettings local_search(const FitSettings& base, int evaluations) {
  FitSettings f = base;
  f.yeoh_start_from_history = false;
  f.statistics = false;
  f.search.algorithm = Algorithm::bobyqa;
  f.search.starts = 1;
  f.search.samples = 0;
  f.search.extra_starts.clear();
  f.search.max_evaluations = evaluations;
  return f;
}

// Stage 1: the new parameters alone; stage 2: every free parameter (DiagnoseSettings budgets).
FitResult staged_refit(const Network& start, const std::vector<int>& kept, const std::vector<int>& added, const std::vector<FitDataSet>& data,
                       const DiagnoseSettings& settings) {
  const int n_added = static_cast<int>(added.size()), n_all = n_added + static_cast<int>(kept.size());
  const int affordable = affordable_evaluations(start, data, settings, 0);
  const bool thorough = affordable >= settings.thorough_evaluations * (n_added + n_all);
  FitSettings first = local_search(settings.fit, thorough ? affordable / 2 : 2 * n_added + 1 + 15 * n_added);
  if (thorough) first.search.algorithm.reset(), first.search.starts = 3, first.search.samples = -1;
  FitResult stage1 = fit(start, added, data, first);
  if (stage1.interrupted || kept.empty()) return stage1;
  std::vector<int> all = kept;
  all.insert(all.end(), added.begin(), added.end());
  std::sort(all.begin(), all.end());
  FitResult stage2 = fit(stage1.network, all, data, local_search(settings.fit, thorough ? affordable / 2 : 2 * n_all + 1 + 4 * n_all));
  stage2.start_values = stage1.start_values;
  stage2.evaluations += stage1.evaluations;
  stage2.non_finite += stage1.non_finite;
  stage2.wall_seconds += stage1.wall_seconds;
  return stage2;
}

// Empty when the resonance of a refitted fluid column (the element ELEMENT of MODEL) lies inside
// the measured frequencies with a margin of 10 % either side, else why not. Shapes without a
// resonance are always resolved.
std::string resolved_resonance(const Trial& trial, const lang::CheckedModel& model, const Network& network, const std::string& element,
                               const DataScales& scales) {
  if (trial.shape != Shape::tuned_column && trial.shape != Shape::capped_column) return {};
  const int k = index_of(model, element + ".chamber.k"), b = index_of(model, element + ".column.mass.b");
  if (k < 0 || b < 0) throw std::logic_error(fmt::format("diagnose: the fluid column '{}' lacks chamber.k or column.mass.b", element));
  const double resonance = std::sqrt(network.parameter(k) / network.parameter(b)) / (2.0 * std::numbers::pi);  // [Hz]
  constexpr double kMargin = 1.1;
  if (resonance >= kMargin * scales.frequency_low && resonance <= scales.frequency_high / kMargin) return {};
  return fmt::format("its resonance, refitted to {:.3g} Hz, is not inside the measured {:.3g}-{:.3g} Hz with a measured frequency 10 % "
                     "either side, so the data cannot tell it from a relaxation or a stiffness trend",
                     resonance, scales.frequency_low, scales.frequency_high);
}

// The limit without inertia (b -> 0) of a refitted slider-capped fluid column ELEMENT: chamber
// spring and channel dashpot in series are a Maxwell element of k = chamber.k and
// tau = channel.c / chamber.k, capped by the same slider: the capped_maxwell shape, one
// parameter fewer and no resonance to place.
Trial resonance_free_limit(const Trial& column, const lang::CheckedModel& model, const Network& refitted, const std::string& element) {
  auto value = [&](const std::string& path) {
    const int i = index_of(model, element + "." + path);
    if (i < 0) throw std::logic_error(fmt::format("diagnose: the fluid column '{}' lacks {}", element, path));
    return refitted.parameter(i);
  };
  Trial limit = column;
  limit.shape = Shape::capped_maxwell;
  limit.stiffness = value("chamber.k");
  limit.time = value("column.channel.c") / limit.stiffness;
  limit.slip = value("cap.fy") / limit.stiffness;
  limit.frequency = limit.damping_ratio = 0.0;
  return limit;
}

// Whether candidate A is preferred to B: the one with fewer parameters when its gap is within
// `parsimony` of the other's (the coupled shapes hold friction and Maxwell elements as limits,
// so they always fit at least as well), else the lower BIC.
bool preferred(const CandidateOutcome& a, const CandidateOutcome& b, double parsimony) {
  if (a.parameters < b.parameters && a.gap_after <= (1.0 + parsimony) * b.gap_after) return true;
  if (b.parameters < a.parameters && b.gap_after <= (1.0 + parsimony) * a.gap_after) return false;
  return a.criterion < b.criterion;
}

struct Chosen {
  std::size_t candidate = 0;
  Trial trial;
  Compiled compiled;  // owns the model result.network refers to
  FitResult result;
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

Diagnosis diagnose(const ModelSource& source, const std::vector<FitDataSet>& data, const DiagnoseSettings& settings) {
  const Compiled base = compile(source, source.text);
  std::vector<int> free;
  if (settings.free.empty()) {
    free = lang::default_free_parameters(*base.model);
  } else {
    for (const auto& path : settings.free) free.push_back(index_of(*base.model, path));
    if (std::count(free.begin(), free.end(), -1)) throw std::logic_error(fmt::format("model '{}': a free parameter is not in it", source.model));
  }
  DiagnoseSettings s = settings;
  s.fit.score.method = FitMethod::exact;
  s.fit.statistics = settings.standard_errors;

  Diagnosis d;
  const bool harmonic = std::any_of(data.begin(), data.end(), [](const FitDataSet& set) { return set.is_harmonic(); });
  d.gap_name = harmonic ? "err (6.1)" : "RMS force residual";
  auto stage = [&](const std::string& what) {
    if (s.stage) s.stage(what);
  };
  stage(fmt::format("fitting model {}", source.model));
  d.before_program = base.program;
  d.before = fit(Network::compile(*base.model), free, data, s.fit);
  d.gap_before = d.gap_after = fit_gap(d.before);
  d.residual_terms = residual_terms(data);
  d.criterion_before = criterion(d.before, d.residual_terms);
  d.patterns = residual_patterns(d.before, data);
  const std::string fitted_text =
      lang::write_fitted_source(source.text, source.file, *base.model, d.before.network.parameters(), d.before.free, {});
  d.interrupted = d.before.interrupted;

  std::vector<std::string> kept_paths;
  for (int i : d.before.free) kept_paths.push_back(base.model->parameters[static_cast<std::size_t>(i)].path);
  const Compiled fitted = compile(source, fitted_text);
  const DataScales scales = data_scales(data);
  std::optional<Chosen> chosen;
  int refitted = 0;
  if (!d.interrupted) stage("screening the effects");
  const std::vector<ScreenedEffect> screened_effects = d.interrupted ? std::vector<ScreenedEffect>{} : screen(d.before, data, s.fit.score);
  const double leading_gain = screened_effects.empty() ? 0.0 : screened_effects.front().gain;
  // Refits the fitted model with TRIAL added as OUTCOME.element, records the outcome and keeps
  // it as the choice if it earns its parameters and beats the choice so far.
  auto refit_candidate = [&](const Trial& trial, CandidateOutcome& outcome) {
    const auto started = std::chrono::steady_clock::now();
    stage(fmt::format("refitting with {} for {}", trial_summary(trial), effect_name(outcome.screened.effect)));
    const std::string comment = fmt::format("candidate for {}", effect_name(outcome.screened.effect));
    Compiled candidate = compile(source, with_trial(fitted_text, *fitted.model, trial, outcome.element, scales.bounds, comment));
    std::vector<int> kept, added;
    for (const auto& path : kept_paths)
      if (const int i = index_of(*candidate.model, path); i >= 0) kept.push_back(i);
    for (std::size_t i = 0; i < candidate.model->parameters.size(); ++i) {
      const lang::Parameter& p = candidate.model->parameters[i];
      if (p.free && p.path.starts_with(outcome.element + ".") && std::find(kept.begin(), kept.end(), static_cast<int>(i)) == kept.end())
        added.push_back(static_cast<int>(i));
    }
    FitResult result = staged_refit(Network::compile(*candidate.model), kept, added, data, s);
    outcome.refitted = true;
    outcome.gap_after = fit_gap(result);
    outcome.criterion = criterion(result, d.residual_terms);
    outcome.parameters = static_cast<int>(result.free.size());
    outcome.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
    d.interrupted = d.interrupted || result.interrupted;
    outcome.unresolved = resolved_resonance(trial, *candidate.model, result.network, outcome.element, scales);
    std::optional<Trial> limit;
    if (trial.shape == Shape::capped_column) limit = resonance_free_limit(trial, *candidate.model, result.network, outcome.element);
    const bool earns = outcome.unresolved.empty() && outcome.criterion < d.criterion_before && outcome.gap_after <= (1.0 - s.min_improvement) * d.gap_before;
    if (earns && (!chosen || preferred(outcome, d.candidates[chosen->candidate], s.parsimony)))
      chosen = Chosen{d.candidates.size(), trial, std::move(candidate), std::move(result)};
    d.candidates.push_back(outcome);
    return limit;
  };
  for (const ScreenedEffect& screened : screened_effects) {
    CandidateOutcome outcome;
    outcome.screened = screened;
    const Trial& trial = screened.trial;
    outcome.element = trial.replaces.empty() ? unique_name(*fitted.model, element_word(screened.effect)) : trial.replaces;
    if (refitted >= s.confirm || screened.gain < std::max(s.min_screen_gain, s.relative_screen_gain * leading_gain) || d.interrupted) {
      d.candidates.push_back(outcome);
      continue;
    }
    ++refitted;
    const std::optional<Trial> limit = refit_candidate(trial, outcome);
    if (!limit || d.interrupted) continue;
    // The column's limit without inertia competes with it: where the data hold no resonance
    // (or cannot place it) the limit earns the coupling with one parameter fewer.
    CandidateOutcome limit_outcome;
    limit_outcome.screened = screened;
    limit_outcome.screened.trial = *limit;
    limit_outcome.element = outcome.element;
    limit_outcome.limit_of = fmt::format("the limit without inertia of the fluid column before it (its chamber and channel as a Maxwell "
                                         "element, tau = c/k = {:.4g} ms){}",
                                         limit->time * 1e3, outcome.unresolved.empty() ? "" : ", whose resonance the data cannot place");
    refit_candidate(*limit, limit_outcome);
  }

  if (!chosen) {
    d.effect = Effect::none;
    d.reason = none_reason(d, s);
    std::vector<std::string> header{fmt::format("Checked by `rheo diagnose`: effect none, nothing added. {} = {:.4g}.", d.gap_name, d.gap_before)};
    d.refined_text = lang::write_fitted_source(source.text, source.file, *base.model, d.before.network.parameters(), d.before.free, header);
    return d;
  }
  d.candidates[chosen->candidate].chosen = true;
  const CandidateOutcome& winner = d.candidates[chosen->candidate];
  if (!d.interrupted) {
    stage("polishing the refined model");
    const int n = static_cast<int>(chosen->result.free.size());
    FitSettings polish = local_search(s.fit, affordable_evaluations(chosen->result.network, data, s, 2 * n + 1 + 20 * n));
    polish.statistics = settings.standard_errors;
    FitResult polished = fit(chosen->result.network, chosen->result.free, data, polish);
    d.interrupted = polished.interrupted;
    if (polished.objective <= chosen->result.objective) {
      polished.start_values = chosen->result.start_values;
      polished.evaluations += chosen->result.evaluations;
      polished.wall_seconds += chosen->result.wall_seconds;
      chosen->result = std::move(polished);
    }
  }
  d.effect = winner.screened.effect;
  d.gap_after = fit_gap(chosen->result);
  d.added_element = winner.element;
  d.reason = effect_reason(d, winner);
  // The final text: the same structure as the refitted candidate, under the comment that says why.
  const std::string comment = fmt::format("added by rheo diagnose: {}; {} {:.4g} -> {:.4g}", effect_name(d.effect), d.gap_name, d.gap_before, d.gap_after);
  const std::string structure = with_trial(fitted_text, *fitted.model, chosen->trial, winner.element, scales.bounds, comment);
  const Compiled refined = compile(source, structure);
  std::vector<std::string> header{fmt::format("Refined by `rheo diagnose`: effect {}; added '{}'; {} {:.4g} -> {:.4g}.", effect_name(d.effect),
                                              winner.element, d.gap_name, d.gap_before, d.gap_after)};
  d.refined_text = lang::write_fitted_source(structure, source.file, *refined.model, chosen->result.network.parameters(), chosen->result.free, header);
  d.added_summary = added_summary(chosen->result, winner.element);
  d.added_statement = statement_lines(d.refined_text, source, winner.element);
  d.after = std::move(chosen->result);
  d.after_program = chosen->compiled.program;
  return d;
}

}  // namespace rheo::runtime::diagnosis
