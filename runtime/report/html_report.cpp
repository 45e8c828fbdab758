#include "runtime/report/html_report.hpp"

#include "runtime/report/network_diagram.hpp"
#include "runtime/report/report_figures.hpp"
#include "runtime/report/svg_text.hpp"

#include <fmt/format.h>

#include <algorithm>

namespace rheo::runtime::report {
namespace {

constexpr const char* kStyle = R"(
body { font-family: Helvetica, Arial, sans-serif; color: #111; max-width: 1320px; margin: 1.5em auto; padding: 0 1em; line-height: 1.4; }
h1 { font-size: 1.6em; margin-bottom: 0.2em; }
h2 { font-size: 1.25em; border-bottom: 1px solid #ccc; padding-bottom: 0.2em; margin-top: 1.8em; }
.meta { color: #444; margin: 0.2em 0; }
code { font-family: Menlo, Consolas, monospace; font-size: 0.95em; }
table { border-collapse: collapse; margin: 0.6em 0; }
th, td { padding: 0.25em 0.7em; border-bottom: 1px solid #ddd; text-align: left; vertical-align: top; }
th { background: #f3f3f3; }
td.num { text-align: right; font-variant-numeric: tabular-nums; }
.figures { display: grid; grid-template-columns: repeat(auto-fill, minmax(460px, 1fr)); gap: 1em 1.5em; }
figure { margin: 0; break-inside: avoid; }
figure svg { display: block; width: 100%; height: auto; }
figure.network svg { width: auto; max-width: 100%; }
figcaption { color: #444; font-size: 0.9em; margin-top: 0.2em; }
h3 { font-size: 1.08em; margin-top: 1.4em; }
pre { background: #f6f6f6; padding: 0.5em 0.8em; overflow-x: auto; }
tr.chosen td { font-weight: bold; }
td.bar { width: 260px; }
div.bar { height: 0.9em; background: #4a7ab5; min-width: 1px; print-color-adjust: exact; -webkit-print-color-adjust: exact; }
@media print {
  body { max-width: none; margin: 0; font-size: 10pt; }
  .figures { grid-template-columns: 1fr 1fr; }
  h2 { break-after: avoid; }
  table, figure { break-inside: avoid; }
}
)";

std::string number(double v) { return fmt::format("{:.6g}", v); }

std::string summary(const ReportContent& c) {
  std::string out = "<h2 id=\"summary\">Summary</h2>\n";
  if (!c.harmonic.empty() || !c.histories.empty()) {
    out += "<table class=\"summary\"><tr><th>data</th><th>kind</th><th>points</th><th>agreement</th></tr>\n";
    for (const HarmonicComparison& h : c.harmonic)
      out += fmt::format("<tr><td><code>{}</code></td><td>harmonic</td><td class=\"num\">{}</td><td>{}</td></tr>\n", escape(h.label),
                         h.amplitude.size(),
                         h.measured() ? fmt::format("&phi; (5.1) = {:.6g}, err (6.1) = {:.4e}{}", h.phi, h.err,
                                                    h.has_baseline() ? fmt::format(" (model before: {:.4e})", h.baseline_err) : "")
                                      : "model only (no measurements)");
    for (const HistoryComparison& h : c.histories)
      out += fmt::format("<tr><td><code>{}</code></td><td>history</td><td class=\"num\">{}</td><td>{}</td></tr>\n", escape(h.label),
                         h.displacement.size(),
                         h.measured() ? fmt::format("force residual RMS {:.3g} %, worst {:.3g} % of max |F|{}", 100.0 * h.rms, 100.0 * h.worst,
                                                    h.has_baseline() ? fmt::format(" (model before: RMS {:.3g} %)", 100.0 * h.baseline_rms) : "")
                                      : "model only (no measurements)");
    out += "</table>\n";
  }
  if (!c.baseline.empty()) out += fmt::format("<p class=\"meta\">Dashed curves: {}.</p>\n", escape(c.baseline));
  if (!c.notes.empty()) {
    out += "<ul class=\"notes\">\n";
    for (const std::string& note : c.notes) out += fmt::format("<li>{}</li>\n", escape(note));
    out += "</ul>\n";
  }
  return out;
}

std::string parameter_table(const ReportContent& c) {
  const bool fitted = std::any_of(c.parameters.begin(), c.parameters.end(), [](const ParameterRow& r) { return r.free; });
  const bool bounded = std::any_of(c.parameters.begin(), c.parameters.end(), [](const ParameterRow& r) { return !r.bounds.empty(); });
  std::string out = "<h2 id=\"parameters\">Parameters</h2>\n<table class=\"parameters\"><tr><th>parameter</th>";
  out += fitted ? "<th>start</th><th>fitted</th><th>std. error</th>" : "<th>value</th>";
  out += fmt::format("<th>unit</th>{}</tr>\n", bounded ? "<th>bounds</th>" : "");
  for (const ParameterRow& r : c.parameters) {
    out += fmt::format("<tr{}><td><code>{}</code></td>", r.free ? " class=\"free\"" : "", escape(r.path));
    if (fitted)
      out += fmt::format("<td class=\"num\">{}</td><td class=\"num\">{}</td><td>{}</td>", r.start ? number(*r.start) : "", number(r.value),
                         r.free ? escape(r.standard_error) : "fixed");
    else out += fmt::format("<td class=\"num\">{}</td>", number(r.value));
    out += fmt::format("<td>{}</td>{}</tr>\n", escape(r.unit), bounded ? fmt::format("<td>{}</td>", escape(r.bounds)) : "");
  }
  return out + "</table>\n";
}

// How the file was read: its TRIOS step, and for material data the geometry that turned moduli
// and strains into stiffness and displacement; empty for a plain table.
std::string source_note(const DataSource& source) {
  std::vector<std::string> parts;
  if (!source.step.empty()) parts.push_back(fmt::format("TRIOS step \"{}\"", source.step));
  if (source.material) {
    std::string geometry;
    if (source.area) geometry += fmt::format("area A = {:g} mm^2", *source.area);
    if (source.height) geometry += fmt::format("{}height h = {:g} mm", geometry.empty() ? "" : ", ", *source.height);
    std::string rules = source.area && source.height ? ": stiffness = modulus x A / h" : "";
    if (source.height) rules += fmt::format("{}amplitude = strain x h", rules.empty() ? ": " : ", ");
    parts.push_back(fmt::format("material data, specimen geometry {}{}", geometry, rules));
  }
  std::string out;
  for (const std::string& part : parts) out += (out.empty() ? "" : "; ") + part;
  return out;
}

std::string curve_caption(const HarmonicComparison& h, const std::string& kind) {
  std::string out = h.measured() ? (h.has_baseline() ? "Markers: measured; lines: refined model; dashed: model before, at the measured points."
                                                     : "Markers: measured; lines: model at the measured points.")
                                 : "Model at the simulated grid points.";
  if (!kind.starts_with("storage") && !kind.starts_with("loss")) return out;
  if (!h.material()) return out + " K' = K cos(phase), K'' = K sin(phase).";
  return out + fmt::format(" E' = K cos(phase) h/A, E'' = K sin(phase) h/A, strain = amplitude/h; A = {:g} mm^2, h = {:g} mm.", *h.source.area,
                           *h.source.height);
}

std::string harmonic_section(const HarmonicComparison& h, std::size_t index) {
  const std::string prefix = fmt::format("h{}", index + 1);
  std::string out = fmt::format("<h2 id=\"{}\">Harmonic: <code>{}</code></h2>\n", prefix, escape(h.label));
  if (const std::string note = source_note(h.source); !note.empty()) out += fmt::format("<p class=\"meta source\">{}</p>\n", escape(note));
  out += "<div class=\"figures\">\n";
  for (const Plot& plot : harmonic_plots(h, prefix)) {
    const std::string kind = plot.id.substr(prefix.size() + 1);
    out += figure_html(kind, render_svg(plot, false), curve_caption(h, kind));
  }
  static const char* const map_kinds[] = {"residual-stiffness", "residual-phase", "residual-stiffness-before", "residual-phase-before"};
  const std::vector<ResidualMap> maps = residual_maps(h);
  for (std::size_t k = 0; k < maps.size(); ++k)
    out += figure_html(map_kinds[k], render_residual_map(maps[k], false),
                       k % 2 == 0 ? "Red: model stiffer than measured; blue: softer." : "Red: model phase above measured; blue: below.");
  return out + "</div>\n";
}

// How the model met the history: where it started, and the force offset it was shown with.
std::string start_and_offset_note(const HistoryComparison& h) {
  std::string out;
  if (!h.displacement.empty() && h.displacement.front() != 0.0)
    out += fmt::format(
        "The model starts relaxed at the first sample's displacement, {:g} mm (rate elements unloaded, friction elements slid to "
        "zero force, springs at their static force).",
        h.displacement.front());
  if (h.offset.free || h.offset.given)
    out += fmt::format("{}The model's force includes the load cell's offset, {:.6g} N ({}).", out.empty() ? "" : " ", h.offset_value,
                       h.offset.free ? "force_offset = free: fitted" : "force_offset as declared on the data line");
  return out;
}

std::string history_section(const HistoryComparison& h, std::size_t index) {
  const std::string id = fmt::format("t{}", index + 1);
  std::string note = source_note(h.source);
  if (const std::string start = start_and_offset_note(h); !start.empty()) note += (note.empty() ? "" : " ") + start;
  return fmt::format("<h2 id=\"{}\">History: <code>{}</code></h2>\n{}<div class=\"figures\">\n{}</div>\n", id, escape(h.label),
                     note.empty() ? "" : fmt::format("<p class=\"meta source\">{}</p>\n", escape(note)),
                     figure_html("hysteresis", render_svg(hysteresis_plot(h, id + "-hysteresis"), false),
                                 h.measured() ? (h.has_baseline() ? "Markers: measured; line: refined model; dashed: model before; "
                                                                    "both driven by the measured displacement."
                                                                  : "Markers: measured; line: model driven by the measured displacement.")
                                              : "Model response."));
}

}  // namespace

std::string html_report(const ReportContent& c) {
  std::string out = fmt::format(
      "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n<title>{}</title>\n<style>{}</style>\n</head>\n"
      "<body>\n<h1>{}</h1>\n",
      escape(c.title), kStyle, escape(c.title));
  out += fmt::format("<p class=\"meta\">Model <code>{}</code> from <code>{}</code></p>\n<p class=\"meta\">{}</p>\n", escape(c.model),
                     escape(c.source), escape(c.origin));
  out += summary(c);
  out += "<h2 id=\"network\">Network</h2>\n" +
         figure_html("network", network_diagram_svg(c.network, "Network of model " + c.model, false),
                     "Series chains run left to right, parallel branches are stacked; ground on the left, the drive u(t) on the right.");
  out += parameter_table(c);
  for (std::size_t k = 0; k < c.harmonic.size(); ++k) out += harmonic_section(c.harmonic[k], k);
  for (std::size_t k = 0; k < c.histories.size(); ++k) out += history_section(c.histories[k], k);
  for (const ReportSection& s : c.sections)
    out += fmt::format("<section id=\"{}\">\n<h2>{}</h2>\n{}</section>\n", escape(s.id), escape(s.title), s.html);
  return out + "</body>\n</html>\n";
}

std::string figure_html(const std::string& kind, const std::string& svg, const std::string& caption) {
  return fmt::format("<figure class=\"plot{}\" data-figure=\"{}\">\n{}<figcaption>{}</figcaption></figure>\n",
                     kind.starts_with("network") ? " network" : "", escape(kind), svg, escape(caption));
}

}  // namespace rheo::runtime::report
