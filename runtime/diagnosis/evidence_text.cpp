#include "runtime/diagnosis/evidence_text.hpp"

#include "lang/frontend.hpp"
#include "lang/source_edit.hpp"
#include "runtime/diagnosis/criterion.hpp"
#include "runtime/fit/fit_report.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <utility>
#include <vector>

namespace rheo::runtime::diagnosis {
namespace {

double degrees(double radians) { return radians * 180.0 / std::numbers::pi; }
double percent(double share) { return 100.0 * share; }

}  // namespace

std::string pattern_sentence(Effect effect, const ResidualPatterns& p) {
  const HarmonicPatterns& h = p.harmonic;
  if (!p.has_harmonic) {
    switch (effect) {
      case Effect::amplitude_dependence: return "the loops' width and corners differ from the model's";
      case Effect::rate_dependence: return "the force residual follows the loading rate";
      case Effect::nonlinear_elasticity: return "the force residual grows with displacement, as stiffening or softening does";
      case Effect::coupled_amplitude_frequency: return "the loop shape changes with amplitude in a way the model's branches cannot follow";
      case Effect::inertia: return "the force residual follows the acceleration";
      case Effect::asymmetry: return "the force residual differs between tension and compression";
      case Effect::backlash: return "the force residual is largest where the loops turn, as free play before contact gives";
      case Effect::offset: return "the force residual has a constant part, as a load cell's zero that is not subtracted gives";
      case Effect::none: return "the force residual shows no pattern an added element explains";
    }
  }
  switch (effect) {
    case Effect::amplitude_dependence:
      return fmt::format("the residual changes with amplitude{} ({:.0f} % of it)", h.interaction_measured() ? " alike at every frequency" : "",
                         percent(h.amplitude_share));
    case Effect::rate_dependence:
      return fmt::format("the residual changes with frequency{} ({:.0f} % of it)", h.interaction_measured() ? " alike at every amplitude" : "",
                         percent(h.frequency_share));
    case Effect::nonlinear_elasticity:
      return fmt::format("the stiffness residual changes with amplitude ({:.0f} % of the residual varies with amplitude alone)",
                         percent(h.amplitude_share));
    case Effect::coupled_amplitude_frequency:
      return fmt::format("the amplitude dependence is not the same at every frequency: the interaction holds {:.0f} % of the residual",
                         percent(h.interaction_share));
    case Effect::inertia:
      return fmt::format("the measured phase exceeds the model's most near {:.3g} Hz (by {:.2f} deg on average over amplitudes)",
                         h.phase_peak_frequency, degrees(h.phase_peak));
    case Effect::asymmetry: return "the loops differ between tension and compression";
    case Effect::backlash:
      return fmt::format(
          "the stiffness residual changes with amplitude ({:.0f} % of the residual varies with amplitude alone), as free "
          "play taken up at larger amplitudes does",
          percent(h.amplitude_share));
    case Effect::offset: return "the histories' force residual has a constant part, as a load cell's zero that is not subtracted gives";
    case Effect::none: break;
  }
  return "the residual shows no pattern an added element explains";
}

std::vector<const CandidateOutcome*> alike_candidates(const Diagnosis& d, const CandidateOutcome& w, double parsimony) {
  auto alike = [&](const CandidateOutcome& c) {
    return &c != &w && c.refitted && c.screened.effect != w.screened.effect && c.unresolved.empty() && c.criterion < d.criterion_before &&
           c.gap_after <= (1.0 + parsimony) * w.gap_after &&
           !(d.noise_weighted && w.parameters > c.parameters && decisively_lower(w.criterion, c.criterion, w.parameters, d.residual_terms));
  };
  std::vector<const CandidateOutcome*> out;
  for (const auto& c : d.candidates) {
    if (!alike(c)) continue;
    const bool better_of_its_effect = std::any_of(d.candidates.begin(), d.candidates.end(), [&](const CandidateOutcome& o) {
      return &o != &c && alike(o) && o.screened.effect == c.screened.effect && o.gap_after < c.gap_after;
    });
    if (!better_of_its_effect) out.push_back(&c);
  }
  return out;
}

namespace {

// "; a yeoh spring in place of ... (nonlinear-elasticity) fits about as well (...)" for each of
// alike_candidates; empty where there is none.
std::string alike_sentences(const Diagnosis& d, const CandidateOutcome& w, double parsimony) {
  std::string out;
  for (const CandidateOutcome* c : alike_candidates(d, w, parsimony)) {
    const int more = c->parameters - w.parameters;
    out += fmt::format("; {} ({}) fits about as well ({} {:.4g}, BIC {:.1f}, {} parameter{} {}): these data do not tell the two apart",
                       trial_summary(c->screened.trial), effect_name(c->screened.effect), d.gap_name, c->gap_after, c->criterion, std::abs(more),
                       std::abs(more) == 1 ? "" : "s", more >= 0 ? "more" : "fewer");
  }
  return out;
}

// "; a yeoh spring ... (nonlinear-elasticity) comes within 10 % of the gap with 1 parameter fewer,
// but ..." for each refitted candidate of another effect that earned with fewer parameters and a
// gap within PARSIMONY of W's, but a decisively higher BIC (criterion.hpp decisively_lower).
std::string outweighed_sentences(const Diagnosis& d, const CandidateOutcome& w, double parsimony) {
  std::string out;
  if (!d.noise_weighted) return out;
  for (const CandidateOutcome& c : d.candidates) {
    if (!c.refitted || c.screened.effect == w.screened.effect || !c.unresolved.empty() || !(c.criterion < d.criterion_before) ||
        c.parameters >= w.parameters || !(c.gap_after <= (1.0 + parsimony) * w.gap_after) ||
        !decisively_lower(w.criterion, c.criterion, w.parameters, d.residual_terms))
      continue;
    const int fewer = w.parameters - c.parameters;
    out += fmt::format(
        "; {} ({}) comes within {:.0f} % of the gap with {} parameter{} fewer ({} {:.4g}), but its BIC is {:.1f} higher, "
        "which the data decide",
        trial_summary(c.screened.trial), effect_name(c.screened.effect), 100.0 * parsimony, fewer, fewer == 1 ? "" : "s", d.gap_name, c.gap_after,
        c.criterion - w.criterion);
  }
  return out;
}

}  // namespace

std::string effect_reason(const Diagnosis& d, const CandidateOutcome& w, double parsimony) {
  // A candidate refitted otherwise than as screened (limit_of): what was screened, then how it was refitted; where that is
  // the same element (fitted from the file's start values), it is named once.
  const std::string summary = trial_summary(w.screened.trial);
  const std::string screened = w.limit_of.empty() ? fmt::format("{} alone would remove {:.0f} % of the objective", summary, percent(w.screened.gain))
                               : w.screened_as == summary ? fmt::format("{} alone would remove {:.0f} % of the objective and, {}, earns it",
                                                                        summary, percent(w.screened.gain), w.limit_of)
                                                          : fmt::format("{} alone would remove {:.0f} % of the objective, and {}, {}, earns it",
                                                                        w.screened_as.empty() ? "a slider-capped fluid column" : w.screened_as,
                                                                        percent(w.screened.gain), summary, w.limit_of);
  const int more = w.parameters - fitted_parameters(d.before);
  return fmt::format(
             "{}; {}; refitted with every parameter, {} fell from {:.4g} to {:.4g} ({:.2f} times lower) and BIC from {:.1f} to "
             "{:.1f} with {} more parameter{}",
             pattern_sentence(w.screened.effect, d.patterns), screened, d.gap_name, d.gap_before, w.gap_after, d.gap_before / w.gap_after,
             d.criterion_before, w.criterion, more, std::abs(more) == 1 ? "" : "s") +
         alike_sentences(d, w, parsimony) + outweighed_sentences(d, w, parsimony);
}

const CandidateOutcome* best_candidate(const Diagnosis& d) {
  const CandidateOutcome* best = nullptr;
  for (const auto& c : d.candidates) {
    if (!c.refitted) continue;
    const bool alike_taken = !d.noise_weighted || !best || c.at_likelihood_maximum == best->at_likelihood_maximum;
    if (!best || (alike_taken ? c.criterion < best->criterion : c.at_likelihood_maximum)) best = &c;
  }
  return best;
}

namespace {

std::string without_noise(const Diagnosis& d, const DiagnoseSettings& s) {
  const CandidateOutcome* best = best_candidate(d);
  if (!best) {
    const double top = d.candidates.empty() ? 0.0 : d.candidates.front().screened.gain;
    return fmt::format(
        "no added element would remove more than {:.1f} % of the objective (threshold {:.0f} %): the residual is at the "
        "level the model's own parameters leave, {} = {:.4g}",
        percent(top), percent(s.min_screen_gain), d.gap_name, d.gap_before);
  }
  if (!best->unresolved.empty())
    return fmt::format("the best candidate, {} for {}, lowered {} from {:.4g} to {:.4g}, but {}; no other candidate earned its parameters",
                       trial_summary(best->screened.trial), effect_name(best->screened.effect), d.gap_name, d.gap_before, best->gap_after,
                       best->unresolved);
  return fmt::format(
      "the best candidate, {} for {}, lowered {} only from {:.4g} to {:.4g} and BIC from {:.1f} to {:.1f}; an element must "
      "lower BIC and the gap{} by {:.0f} % to earn its parameters",
      trial_summary(best->screened.trial), effect_name(best->screened.effect), d.gap_name, d.gap_before, best->gap_after, d.criterion_before,
      best->criterion, d.noise_weighted ? " or its residual over the noise" : "", percent(s.min_improvement));
}

std::string range_text(const LevelRange& r, const char* unit) {
  if (r.levels == r.of) return fmt::format("spread over all {} levels", r.of);
  const std::string where = r.low == r.high ? fmt::format("{:.4g} {}", r.low, unit) : fmt::format("{:.4g}-{:.4g} {}", r.low, r.high, unit);
  return fmt::format("{:.0f} % at {} ({} of {} levels)", percent(r.share), where, r.levels, r.of);
}

}  // namespace

std::string noise_sentence(const Diagnosis& d) {
  const NoiseEstimate& n = d.noise;
  if (!n.estimated) return {};
  const std::string what =
      d.patterns.has_harmonic
          ? fmt::format("from the residual's roughness over the amplitude x frequency grid: {:.2f} % in stiffness, {:.3f} deg in phase",
                        100.0 * n.stiffness, degrees(n.phase))
          : fmt::format("from the force residual's roughness in time: {:.3f} % of max|F| (lag-1 autocorrelation of the residual {:.2f})",
                        100.0 * n.force, n.autocorrelation);
  // Where the noise's size varies over the grid (noise_profile.hpp): its law, the sizes above being RMS.
  std::vector<std::string> laws;
  for (const auto& [name, p] : {std::pair{"stiffness", &n.stiffness_profile}, std::pair{"phase", &n.phase_profile}})
    if (d.patterns.has_harmonic && p->varies)
      laws.push_back(fmt::format("the {} noise's variance as a^{:.2f} f^{:.2f}", name, p->amplitude_slope, p->frequency_slope));
  const std::string varies = laws.empty() ? "" : fmt::format(" (RMS over the points; {})", fmt::join(laws, ", "));
  std::string out = fmt::format("measurement noise estimated {}{}; noise alone leaves {} = {:.4g} (+-{:.0f} %), and the gap is {:.2f} times that",
                                what, varies, d.gap_name, n.floor, percent(n.relative_error), d.noise_ratio);
  if (d.chi_square_ratio > 0.0)
    out += fmt::format("; weighted by the noise, the model's least chi^2 is {:.4g} for N - p = {}, the residual {:.2f} times the noise",
                       d.chi_square_before, d.residual_terms - static_cast<int>(d.before.free.size()), d.chi_square_ratio);
  return out;
}

std::string none_reason(const Diagnosis& d, const DiagnoseSettings& s) {
  const std::string noise = noise_sentence(d);
  return without_noise(d, s) + (noise.empty() ? ", so the residual is taken as noise" : "; the residual is noise: " + noise);
}

std::string unexplained_reason(const Diagnosis& d) {
  std::string out = fmt::format("the residual is systematic but no candidate explains it: {}", noise_sentence(d));
  if (d.unexplained) {
    const ResidualShape& shape = *d.unexplained;
    if (shape.amplitudes && shape.frequencies)
      out += fmt::format("; its square lies {} of amplitude and {} of frequency", range_text(*shape.amplitudes, "mm"),
                         range_text(*shape.frequencies, "Hz"));
    if (d.patterns.has_harmonic) {
      const HarmonicPatterns& h = d.patterns.harmonic;
      out += fmt::format(
          "; {:.0f} % of it varies with amplitude alone, {:.0f} % with frequency alone, {:.0f} % with both together; RMS {:.2f} % in "
          "stiffness and {:.3f} deg in phase, largest {:+.2f} % at {:.4g} mm, {:.4g} Hz",
          percent(h.amplitude_share), percent(h.frequency_share), percent(h.interaction_share), 100.0 * h.stiffness_rms, degrees(h.phase_rms),
          100.0 * h.worst_stiffness.residual, h.worst_stiffness.amplitude, h.worst_stiffness.frequency);
    }
    if (shape.resembles)
      out += fmt::format("; the force residual resembles {} ({:.0f} % of its square)", resemblance_name(*shape.resembles),
                         percent(shape.resembles_share));
    for (const auto& h : d.patterns.histories)
      out += fmt::format("; {}: largest {:.2f} % of max|F| at u = {:.4g} mm", h.path, 100.0 * h.worst, h.worst_displacement);
  }
  if (const CandidateOutcome* best = best_candidate(d))
    out += fmt::format("; the best candidate, {} for {}, lowered {} only from {:.4g} to {:.4g} (BIC {:.1f} -> {:.1f}){}",
                       trial_summary(best->screened.trial), effect_name(best->screened.effect), d.gap_name, d.gap_before, best->gap_after,
                       d.criterion_before, best->criterion, best->unresolved.empty() ? "" : ", and " + best->unresolved);
  else if (!d.candidates.empty())
    out += fmt::format("; the leading screened element, {} for {}, would remove only {:.1f} % of the objective",
                       trial_summary(d.candidates.front().screened.trial), effect_name(d.candidates.front().screened.effect),
                       percent(d.candidates.front().screened.gain));
  return out + ": an effect outside the vocabulary, or a model that needs more than one element at once";
}

std::string added_summary(const FitResult& refit, const std::string& element) {
  std::string out;
  const lang::CheckedModel& model = refit.network.model();
  for (std::size_t i = 0; i < model.parameters.size(); ++i) {
    const lang::Parameter& p = model.parameters[i];
    if (!p.path.starts_with(element + ".") || p.value_begin < 0) continue;
    out += fmt::format("{}{} = {:.4g} {}", out.empty() ? "" : ", ", p.path, in_written_unit(p, refit.network.parameter(static_cast<int>(i))),
                       written_unit(p));
  }
  return out;
}

std::vector<std::string> statement_lines(const std::string& text, const ModelSource& source, const std::string& element) {
  const lang::Program program = lang::compile_source(source.file, text);
  for (const auto& e : program.find_model(source.model)->root.children)
    if (e.name == element) {
      const lang::TextSpan span = lang::element_statement(text, e);
      std::vector<std::string> lines;
      std::string_view rest = std::string_view(text).substr(span.begin, span.end - span.begin);
      while (!rest.empty()) {
        const std::size_t newline = rest.find('\n');
        std::string line(rest.substr(0, newline));
        const std::size_t indent = lang::line_indent(text, span.begin).size();
        if (!lines.empty() && line.size() >= indent && line.find_first_not_of(' ') >= indent) line.erase(0, indent);
        lines.push_back(line);
        rest = newline == std::string_view::npos ? std::string_view() : rest.substr(newline + 1);
      }
      return lines;
    }
  return {};
}

std::vector<std::string> pattern_lines(const ResidualPatterns& p) {
  std::vector<std::string> lines;
  if (p.has_harmonic) {
    const HarmonicPatterns& h = p.harmonic;
    lines.push_back(fmt::format("harmonic: {} points; RMS stiffness residual {:.2f} %, RMS phase residual {:.3f} deg", h.points,
                                100.0 * h.stiffness_rms, degrees(h.phase_rms)));
    lines.push_back(
        fmt::format("largest stiffness residual {:+.2f} % at {:.4g} mm, {:.4g} Hz; largest phase residual {:+.3f} deg at {:.4g} mm, "
                    "{:.4g} Hz (model - measured)",
                    100.0 * h.worst_stiffness.residual, h.worst_stiffness.amplitude, h.worst_stiffness.frequency, degrees(h.worst_phase.residual),
                    h.worst_phase.amplitude, h.worst_phase.frequency));
    if (h.interaction_measured())
      lines.push_back(
          fmt::format("share of the residual that varies with amplitude alone {:.0f} %, with frequency alone {:.0f} %, with both "
                      "together (interaction) {:.0f} %",
                      percent(h.amplitude_share), percent(h.frequency_share), percent(h.interaction_share)));
    else
      lines.push_back(
          fmt::format("share of the residual that varies with amplitude {:.0f} %, with frequency {:.0f} %; whether the two act together is not "
                      "measured: no two amplitudes share two frequencies (a grid, not single sweeps, measures it), so coupled-amplitude-frequency "
                      "is not a candidate",
                      percent(h.amplitude_share), percent(h.frequency_share)));
    if (h.phase_peak > 0.0)
      lines.push_back(fmt::format("the measured phase exceeds the model's most near {:.4g} Hz: {:.3f} deg on average over amplitudes",
                                  h.phase_peak_frequency, degrees(h.phase_peak)));
  }
  for (const auto& history : p.histories)
    lines.push_back(fmt::format("{}: RMS force residual {:.3f} % of max|F|, largest {:.3f} % at u = {:.4g} mm", history.path, 100.0 * history.rms,
                                100.0 * history.worst, history.worst_displacement));
  return lines;
}

}  // namespace rheo::runtime::diagnosis
