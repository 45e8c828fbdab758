#include "runtime/diagnosis/diagnose.hpp"

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

Compiled compile(const ModelSource& source, const std::string& text) {
  auto program = std::make_shared<const lang::Program>(lang::compile_source(source.file, text));
  const lang::CheckedModel* model = program->find_model(source.model);
  if (!model) throw std::logic_error(fmt::format("{} has no model '{}'", source.file, source.model));
  return {program, model};
}

double fit_gap(const FitResult& result) {
  if (result.err > 0.0) return result.err;
  double sum = 0.0;
  int histories = 0;
  for (const auto& set : result.datasets)
    if (!set.harmonic) sum += set.err * set.err, ++histories;
  return histories ? std::sqrt(sum / histories) : result.err;
}

void Diagnoser::stage(const std::string& what) const {
  if (s_.stage) s_.stage(what);
}

double Diagnoser::time_left() const {
  if (!s_.deadline) return std::numeric_limits<double>::infinity();
  return std::chrono::duration<double>(*s_.deadline - std::chrono::steady_clock::now()).count();
}

bool Diagnoser::stopped() {
  if (!d_.interrupted && time_left() <= 0.0) d_.time_limited = true;
  return d_.interrupted || d_.time_limited;
}

DiagnoseSettings Diagnoser::within(double share) const {
  DiagnoseSettings s = s_;
  if (const double left = time_left(); std::isfinite(left))
    s.fit.time_limit = std::min(s.fit.time_limit.value_or(1e300), std::max(1e-3, share * left));
  return s;
}

std::vector<int> Diagnoser::free_parameters() const {
  if (settings_.free.empty()) return lang::default_free_parameters(*base_.model);
  std::vector<int> free;
  for (const auto& path : settings_.free) free.push_back(parameter_index(*base_.model, path));
  if (std::count(free.begin(), free.end(), -1)) throw std::logic_error(fmt::format("model '{}': a free parameter is not in it", source_.model));
  return free;
}

void Diagnoser::fit_model() {
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

std::vector<ScreenedEffect> Diagnoser::screen_effects() {
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

void Diagnoser::polish() {
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

Diagnosis Diagnoser::finish_none() {
  d_.effect = Effect::none;
  // The closest candidate's BIC at its likelihood's maximum, as the model's is, for the reason's
  // comparison (its refit's, by eq. 5.1, can lie far above: 12121 against the model's 1046).
  if (closest_ && !stopped() && !d_.candidates[closest_->candidate].at_likelihood_maximum)
    at_likelihood_maximum(d_.candidates[closest_->candidate], closest_->result, *closest_->data, 1.0);
  const bool beyond_noise = residual_beyond_noise();
  d_.verdict = beyond_noise ? Verdict::unexplained : Verdict::none;
  if (beyond_noise) d_.unexplained = residual_shape(d_.before, data_);
  d_.reason = beyond_noise ? unexplained_reason(d_) : none_reason(d_, s_);
  const std::string noise = d_.noise.estimated ? fmt::format(" (the noise leaves {:.4g})", d_.noise.floor) : "";
  std::vector<std::string> header{fmt::format("Checked by `rheo diagnose`: {}, nothing added. {} = {:.4g}{}.",
                                              beyond_noise ? "unexplained: a systematic residual no candidate removes" : "effect none", d_.gap_name,
                                              d_.gap_before, noise)};
  d_.refined_text = lang::write_fitted_source(source_.text, source_.file, *base_.model, d_.before.network.parameters(), d_.before.free, header);
  return std::move(d_);
}

Diagnosis Diagnoser::finish_refined() {
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

Diagnosis Diagnoser::finish_offset() {
  d_.freed_offsets = fixed_offsets(data_);
  const std::vector<lang::FitData> lines = fit_block_lines(*base_.program, source_.fit_block, data_.size());
  const OffsetText text = offset_text(source_.text, source_.file, lines, d_.freed_offsets, chosen_->result);
  d_.added_element = "force_offset";
  d_.added_summary = text.summary;
  d_.added_statement = text.statement;
  const std::vector<std::string> header = offset_header(text, d_.freed_offsets.size(), d_.gap_name, d_.gap_before, d_.gap_after);
  d_.refined_text = lang::write_fitted_source(source_.text, source_.file, *base_.model, chosen_->result.network.parameters(), chosen_->result.free,
                                              header, text.edits);
  d_.after = std::move(chosen_->result);
  d_.after_program = chosen_->compiled.program;
  return std::move(d_);
}


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
