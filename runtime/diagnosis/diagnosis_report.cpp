#include "runtime/diagnosis/diagnosis_report.hpp"

#include "runtime/diagnosis/evidence_text.hpp"
#include "runtime/fit/fit_report.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <nlohmann/json.hpp>

#include <numbers>

namespace rheo::runtime::diagnosis {
namespace {

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }

std::string data_lines(const FitResult& r) {
  std::string out;
  for (const DataSetFit& set : r.datasets)
    out += fmt::format("  data {} ({}, {} {})\n", set.path, set.harmonic ? "harmonic" : "history",
                       set.harmonic ? set.prediction.points.size() : set.prediction.force.size(), set.harmonic ? "points" : "samples");
  return out;
}

}  // namespace

std::string diagnosis_report_text(const std::string& source_file, const Diagnosis& d) {
  std::string out = fmt::format("rheo diagnose: model {} from {}\n", d.before.network.model().name, source_file);
  out += data_lines(d.before);
  out += fmt::format("  fitted {} parameters: {} = {:.4g}, BIC = {:.1f} over {} residual terms\n\n", d.before.free.size(), d.gap_name, d.gap_before,
                     d.criterion_before, d.residual_terms);
  out += "where the model misses\n";
  for (const auto& line : pattern_lines(d.patterns)) out += "  " + line + "\n";
  if (const std::string noise = noise_sentence(d); !noise.empty()) out += "  " + noise + "\n";
  out += "\ncandidates (screened: share of the objective the element removes alone; refitted: with every free parameter)\n";
  // Where the model's BIC is at its likelihood's maximum and a candidate's is its refit's (an
  // upper bound: diagnose.hpp step 4), the candidate's is marked.
  const bool marked = d.noise_weighted && std::any_of(d.candidates.begin(), d.candidates.end(),
                                                      [](const CandidateOutcome& c) { return c.refitted && !c.at_likelihood_maximum; });
  out += fmt::format("  {:<28}  {:>8}  {:>12}  {:>10}{}  {}\n", "effect", "screened", d.gap_name, "BIC", marked ? " " : "", "element");
  for (const auto& c : d.candidates) {
    const std::string mark = !marked ? "" : c.refitted && !c.at_likelihood_maximum ? "*" : " ";
    const std::string refit = c.refitted ? fmt::format("{:>12.4g}  {:>10.1f}{}", c.gap_after, c.criterion, mark)
                                         : fmt::format("{:>12}  {:>10}{}", "-", "-", marked ? " " : "");
    out += fmt::format("  {:<28}  {:>6.1f} %  {}  {}{}\n", effect_name(c.screened.effect), 100.0 * c.screened.gain, refit,
                       trial_summary(c.screened.trial), c.chosen ? "  <- chosen" : "");
  }
  if (marked)
    out += "  * BIC of the refit as it ended (by eq. 5.1), an upper bound of its value at the likelihood's maximum, where the model's is taken\n";
  for (const auto& c : d.candidates)
    if (!c.unresolved.empty()) out += fmt::format("  {} cannot earn: {}\n", effect_name(c.screened.effect), c.unresolved);
    else if (!c.limit_of.empty())
      out += fmt::format("  {} also tried as {}: {}\n", effect_name(c.screened.effect), trial_summary(c.screened.trial), c.limit_of);
  out += fmt::format("\neffect: {}\n  why: {}\n", verdict_name(d), d.reason);
  if (d.verdict == Verdict::named) {
    out += fmt::format("  {}: {:.4g} -> {:.4g} after a final polish ({:.2f} times lower)\n", d.gap_name, d.gap_before, d.gap_after,
                       d.gap_before / d.gap_after);
    out += fmt::format("  added to model {}:\n", d.before.network.model().name);
    for (const auto& line : d.added_statement) out += "    " + line + "\n";
    if (d.after)
      for (const std::string& note : bound_notes(*d.after)) out += "  " + note + "\n";
  } else {
    out += "  nothing added\n";
  }
  if (d.interrupted) out += "  interrupted: the results so far\n";
  if (d.time_limited) out += "  stopped at the time limit: the results so far\n";
  return out;
}

std::string diagnosis_report_json(const std::string& source_file, const Diagnosis& d, const std::string& output) {
  using nlohmann::json;
  json evidence{{"reason", d.reason}, {"patterns", pattern_lines(d.patterns)}};
  if (d.patterns.has_harmonic) {
    const HarmonicPatterns& h = d.patterns.harmonic;
    evidence["harmonic"] = {
        {"points", h.points},
        {"stiffness_rms", h.stiffness_rms},
        {"phase_rms_deg", degrees(h.phase_rms)},
        {"amplitude_share", h.amplitude_share},
        {"frequency_share", h.frequency_share},
        {"interaction_share", h.interaction_share},
        {"interaction_measured", h.interaction_measured()},
        {"worst_stiffness",
         {{"amplitude_mm", h.worst_stiffness.amplitude}, {"frequency_hz", h.worst_stiffness.frequency}, {"residual", h.worst_stiffness.residual}}},
        {"worst_phase",
         {{"amplitude_mm", h.worst_phase.amplitude}, {"frequency_hz", h.worst_phase.frequency}, {"residual_deg", degrees(h.worst_phase.residual)}}},
        {"phase_peak", {{"frequency_hz", h.phase_peak_frequency}, {"excess_deg", degrees(h.phase_peak)}}}};
  }
  json histories = json::array();
  for (const auto& h : d.patterns.histories)
    histories.push_back({{"file", h.path}, {"rms", h.rms}, {"max", h.worst}, {"worst_displacement_mm", h.worst_displacement}});
  evidence["histories"] = histories;
  json candidates = json::array();
  for (const auto& c : d.candidates) {
    json e{{"effect", effect_name(c.screened.effect)}, {"screened_gain", c.screened.gain}, {"element", c.element},
           {"trial", trial_summary(c.screened.trial)}, {"refitted", c.refitted},           {"chosen", c.chosen}};
    if (!c.unresolved.empty()) e["unresolved"] = c.unresolved;
    if (!c.limit_of.empty()) e["limit_of"] = c.limit_of;
    if (c.refitted)
      e["gap_after"] = c.gap_after, e["criterion"] = c.criterion, e["at_likelihood_maximum"] = c.at_likelihood_maximum,
      e["parameters"] = c.parameters, e["wall_seconds"] = c.wall_seconds;
    if (c.refitted && !c.fitted.empty()) e["fitted"] = c.fitted;
    candidates.push_back(e);
  }
  evidence["candidates"] = candidates;
  const NoiseEstimate& n = d.noise;
  evidence["noise"] = n.estimated ? json{{"floor", n.floor},
                                         {"relative_error", n.relative_error},
                                         {"ratio", d.noise_ratio},
                                         {"pseudo_residuals", n.pseudo_residuals}}
                                  : json(nullptr);
  if (n.estimated && d.patterns.has_harmonic) evidence["noise"]["stiffness"] = n.stiffness, evidence["noise"]["phase_deg"] = degrees(n.phase);
  // The variance's power law over the grid (noise_profile.hpp), where it varies.
  for (const auto& [name, profile] : {std::pair{"stiffness_profile", &n.stiffness_profile}, std::pair{"phase_profile", &n.phase_profile}})
    if (n.estimated && profile->varies)
      evidence["noise"][name] = json{{"amplitude_slope", profile->amplitude_slope}, {"frequency_slope", profile->frequency_slope}};
  if (d.chi_square_ratio > 0.0)
    evidence["noise"]["least_chi_square"] = d.chi_square_before, evidence["noise"]["chi_square_ratio"] = d.chi_square_ratio;
  if (n.estimated && !d.patterns.has_harmonic) evidence["noise"]["force"] = n.force, evidence["noise"]["autocorrelation"] = n.autocorrelation;

  json alike = json::array();
  for (Effect e : d.alike) alike.push_back(effect_name(e));
  json j{{"effect", verdict_name(d)},  {"alike", alike},          {"evidence", evidence}, {"gap_measure", d.gap_name},
         {"err_before", d.gap_before}, {"err_after", d.gap_after}};
  json criterion{{"name", "BIC"}, {"residual_terms", d.residual_terms}, {"noise_weighted", d.noise_weighted}, {"before", d.criterion_before}};
  json added = json::array();
  if (d.after) {
    criterion["after"] = d.criterion_before;
    for (const auto& c : d.candidates)
      if (c.chosen) criterion["after"] = c.criterion;
    json parameters = json::array();
    const lang::CheckedModel& model = d.after->network.model();
    for (std::size_t i = 0; i < model.parameters.size(); ++i) {
      const lang::Parameter& p = model.parameters[i];
      if (p.path.starts_with(d.added_element + ".") && p.value_begin >= 0)
        parameters.push_back(
            {{"path", p.path}, {"value", in_written_unit(p, d.after->network.parameter(static_cast<int>(i)))}, {"unit", written_unit(p)}});
    }
    for (std::size_t k : d.freed_offsets)  // the effect offset: the data lines' fitted force offsets
      parameters.push_back({{"path", fmt::format("data {}: force_offset", d.after->datasets.at(k).path)},
                            {"value", d.after->datasets.at(k).force_offset.value},
                            {"unit", "N"}});
    added.push_back({{"element", d.added_element}, {"effect", effect_name(d.effect)}, {"statement", d.added_statement}, {"parameters", parameters}});
  }
  j["criterion"] = criterion;
  j["added"] = added;
  j["at_bounds"] = d.after ? bound_notes(*d.after) : std::vector<std::string>{};
  j["model"] = d.refined_text;
  j["model_name"] = d.before.network.model().name;
  j["source"] = source_file;
  j["output"] = output.empty() ? json(nullptr) : json(output);
  j["interrupted"] = d.interrupted;
  j["time_limited"] = d.time_limited;
  j["unexplained"] = nullptr;
  if (d.unexplained) {
    auto range = [](const std::optional<LevelRange>& r, const char* unit) {
      return r ? json{{std::string("low_") + unit, r->low}, {std::string("high_") + unit, r->high}, {"share", r->share}, {"levels", r->levels}}
               : json(nullptr);
    };
    json u{{"reason", d.reason},
           {"amplitudes", range(d.unexplained->amplitudes, "mm")},
           {"frequencies", range(d.unexplained->frequencies, "hz")},
           {"resembles", d.unexplained->resembles ? json(resemblance_name(*d.unexplained->resembles)) : json(nullptr)},
           {"resembles_share", d.unexplained->resembles_share},
           {"best_candidate", nullptr}};
    if (const CandidateOutcome* best = best_candidate(d))
      u["best_candidate"] = {{"effect", effect_name(best->screened.effect)},
                             {"trial", trial_summary(best->screened.trial)},
                             {"gap_after", best->gap_after},
                             {"criterion", best->criterion},
                             {"parameters", best->parameters}};
    j["unexplained"] = u;
  }
  return j.dump(2) + "\n";
}

}  // namespace rheo::runtime::diagnosis
