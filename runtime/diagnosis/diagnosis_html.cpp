#include "runtime/diagnosis/diagnosis_html.hpp"

#include "runtime/diagnosis/evidence_text.hpp"
#include "runtime/diagnosis/trial.hpp"
#include "runtime/report/html_report.hpp"
#include "runtime/report/network_diagram.hpp"
#include "runtime/report/svg_text.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

namespace rheo::runtime::diagnosis {
namespace {

using report::escape;

const FitResult& final_fit(const Diagnosis& d) { return d.after ? *d.after : d.before; }

// The gap as fitted and after every round, each with a bar as long as its share of the start.
std::string gap_table(const std::vector<Diagnosis>& rounds) {
  const double start = rounds.front().gap_before;
  const auto row = [&](const std::string& stage, double gap) {
    const double share = start > 0.0 ? std::clamp(gap / start, 0.0, 1.0) : 0.0;
    return fmt::format(
        "<tr><td>{}</td><td class=\"num\">{:.4g}</td><td class=\"num\">{:.3g}</td>"
        "<td class=\"bar\"><div class=\"bar\" style=\"width: {:.1f}%\"></div></td></tr>\n",
        stage, gap, gap > 0.0 ? start / gap : 1.0, 100.0 * share);
  };
  std::string out = fmt::format("<table class=\"gap\"><tr><th>model</th><th>{}</th><th>times lower</th><th></th></tr>\n",
                                escape(rounds.front().gap_name));
  out += row("as given, fitted", start);
  for (std::size_t k = 0; k < rounds.size(); ++k) {
    const Diagnosis& d = rounds[k];
    const std::string what = d.verdict != Verdict::named ? fmt::format("nothing added ({})", verdict_name(d))
                                                         : fmt::format("<code>{}</code> added ({})", escape(d.added_element), effect_name(d.effect));
    out += row(fmt::format("round {}: {}", k + 1, what), d.gap_after);
  }
  return out + "</table>\n";
}

std::string candidate_table(const Diagnosis& d) {
  std::string out = fmt::format(
      "<table class=\"candidates\"><tr><th>effect</th><th>screened</th><th>{} refitted</th><th>BIC</th>"
      "<th>parameters</th><th>element tried</th><th></th></tr>\n",
      escape(d.gap_name));
  out += fmt::format(
      "<tr><td>(model as given)</td><td></td><td class=\"num\">{:.4g}</td><td class=\"num\">{:.1f}</td><td class=\"num\">{}</td>"
      "<td></td><td></td></tr>\n",
      d.gap_before, d.criterion_before, d.before.free.size());
  for (const CandidateOutcome& c : d.candidates) {
    std::string note = c.chosen ? "chosen" : "";
    if (!c.limit_of.empty()) note += (note.empty() ? "" : "; ") + c.limit_of;
    if (!c.unresolved.empty()) note = "cannot earn: " + c.unresolved;
    out += fmt::format("<tr{}><td>{}</td><td class=\"num\">{:.1f} %</td>", c.chosen ? " class=\"chosen\"" : "", effect_name(c.screened.effect),
                       100.0 * c.screened.gain);
    if (c.refitted)
      out += fmt::format("<td class=\"num\">{:.4g}</td><td class=\"num\">{:.1f}{}</td><td class=\"num\">{}</td>", c.gap_after, c.criterion,
                         d.noise_weighted && !c.at_likelihood_maximum ? "*" : "", c.parameters);
    else out += "<td>not refitted</td><td></td><td></td>";
    out += fmt::format("<td>{}</td><td>{}</td></tr>\n", escape(trial_summary(c.screened.trial)), escape(note));
  }
  out += "</table>\n";
  if (d.noise_weighted &&
      std::any_of(d.candidates.begin(), d.candidates.end(), [](const CandidateOutcome& c) { return c.refitted && !c.at_likelihood_maximum; }))
    out += "<p>* BIC of the refit as it ended (by eq. 5.1), an upper bound of its value at the likelihood's maximum, where the model's is taken.</p>\n";
  return out;
}

std::string round_html(const Diagnosis& d, std::size_t index, bool several) {
  std::string out = several ? fmt::format("<h3>Round {}: {}</h3>\n", index + 1, verdict_name(d))
                            : fmt::format("<h3>Effect: {}</h3>\n", verdict_name(d));
  out += fmt::format("<p>{}</p>\n<p>Where the model as fitted missed:</p>\n<ul>\n", escape(d.reason));
  for (const std::string& line : pattern_lines(d.patterns)) out += fmt::format("<li>{}</li>\n", escape(line));
  if (const std::string noise = noise_sentence(d); !noise.empty()) out += fmt::format("<li>{}</li>\n", escape(noise));
  out +=
      "</ul>\n<p>Candidates: the share of the objective the element removes alone (screened), then the gap and BIC "
      "after refitting it with every free parameter. A candidate earns when its BIC is lower and the gap drops enough.</p>\n";
  out += candidate_table(d);
  if (d.verdict == Verdict::unexplained)
    return out + "<p>Nothing added: the residual is more than the noise, but no candidate element removes it (verdict unexplained).</p>\n";
  if (d.verdict != Verdict::named) return out + "<p>Nothing added.</p>\n";
  out += fmt::format("<p>Added to model <code>{}</code> ({}), then every free parameter polished: {} {:.4g} &rarr; {:.4g}.</p>\n",
                     escape(d.before.network.model().name), escape(d.added_summary), escape(d.gap_name), d.gap_before, d.gap_after);
  std::string statement;
  for (const std::string& line : d.added_statement) statement += escape(line) + "\n";
  return out + fmt::format("<pre><code>{}</code></pre>\n", statement);
}

}  // namespace

report::ReportContent diagnosis_report_content(const std::vector<Diagnosis>& rounds, const std::vector<FitDataSet>& data,
                                               const FitDescription& description, const std::string& command) {
  if (rounds.empty()) throw std::logic_error("diagnosis_report_content: no rounds");
  const Diagnosis& first = rounds.front();
  const Diagnosis& last = rounds.back();
  report::ReportContent content = report::report_from_fit(final_fit(last), data, description);
  const std::string model = first.before.network.model().name;
  const bool added = std::any_of(rounds.begin(), rounds.end(), [](const Diagnosis& d) { return d.verdict == Verdict::named; });
  content.title = fmt::format("{}: model {}", command, model);
  content.origin = fmt::format("{}: {} {:.4g} -> {:.4g} in {} round{}; fits: method {}, objective {}, seed {}", command, first.gap_name,
                               first.gap_before, last.gap_after, rounds.size(), rounds.size() == 1 ? "" : "s", description.method,
                               description.objective, description.seed);
  if (added)
    report::add_baseline(content, first.before, fmt::format("model {} as given, fitted ({} {:.4g})", model, first.gap_name, first.gap_before));

  const bool several = rounds.size() > 1;
  std::string html = gap_table(rounds);
  for (std::size_t k = 0; k < rounds.size(); ++k) html += round_html(rounds[k], k, several);
  if (added)
    html += report::figure_html("network-before",
                                report::network_diagram_svg(first.before.network.model().root, "Network of model " + model + " as given", false),
                                "The network before the first round; the refined network is drawn above.");
  content.sections.push_back({"diagnosis", several ? "Refinement" : "Diagnosis", html});
  if (last.interrupted) content.notes.push_back("interrupted: the results so far");
  if (last.time_limited) content.notes.push_back("stopped at the time limit: the results so far");
  return content;
}

}  // namespace rheo::runtime::diagnosis
