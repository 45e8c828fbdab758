#include "runtime/report/html_report.hpp"
#include "runtime/core/errors.hpp"
#include "runtime/report/report_figures.hpp"
#include "report_support.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace html_report_test {

using namespace rheo;
using rheo::test::count;

namespace {

// A 3 x 4 harmonic grid of a Kelvin-Voigt model, "measured" 1 % stiffer, and a short history.
runtime::report::ReportContent sample_content() {
  const runtime::Network network = test::network_from("model kv { spring k (k = 100 N/mm in [1, 1000])\n dashpot c (c = 0.5 N*s/mm) }", "kv");
  runtime::report::ReportContent content = runtime::report::report_for_model(network, "dir/<odd> & name.rheo", "rheo report");
  runtime::report::HarmonicComparison grid;
  grid.label = "data/grid.csv";
  for (const double a : {0.1, 0.5, 2.0})
    for (const double f : {1.0, 5.0, 20.0, 50.0}) {
      const double w = 2 * M_PI * f;
      grid.amplitude.push_back(a), grid.frequency.push_back(f);
      grid.model_stiffness.push_back(std::hypot(100.0, 0.5 * w)), grid.model_phase.push_back(std::atan2(0.5 * w, 100.0));
      grid.measured_stiffness.push_back(1.01 * grid.model_stiffness.back()), grid.measured_phase.push_back(grid.model_phase.back() + 0.01);
    }
  content.harmonic.push_back(grid);
  content.histories.push_back({"data/loop.csv", {0, 1, 0, -1, 0}, {0, 100, 10, -100, -10}, {0, 98, 12, -99, -11}, 0.01, 0.02, {}, 0.0});
  content.sections.push_back({"gap", "Gap before and after", "<p>before 1e-2, after 1e-3</p>"});
  return content;
}

}  // namespace

TEST_CASE("report html: self-contained, no script, every figure and section present") {
  const std::string html = runtime::report::html_report(sample_content());
  CHECK(html.starts_with("<!DOCTYPE html>"));
  CHECK(html.find("http") == std::string::npos);
  CHECK(html.find("<script") == std::string::npos);
  CHECK(html.find("src=") == std::string::npos);
  CHECK(html.find("@import") == std::string::npos);
  CHECK(count(html, "url(") == count(html, "url(#clip-"));  // only in-page clip paths
  CHECK(count(html, "<figure") == 10);                      // network, 4 curves, storage and loss, 2 residual maps, 1 loop
  for (const char* kind : {"network", "stiffness-frequency", "phase-frequency", "stiffness-amplitude", "phase-amplitude", "storage-frequency",
                           "loss-frequency", "residual-stiffness", "residual-phase", "hysteresis"})
    CHECK(count(html, fmt::format("data-figure=\"{}\"", kind)) == 1);
  // 3 amplitudes x (measured + model) over frequency in 4 plots (stiffness, phase, storage,
  // loss), 4 frequencies x 2 over amplitude in 2, 2 loops.
  CHECK(count(html, "class=\"series\"") == 4 * 6 + 2 * 8 + 2);
  CHECK(html.find("class=\"meta source\"") == std::string::npos);  // a plain table: nothing to say about its reading
  CHECK(count(html, "class=\"cell\"") == 2 * 12);
  CHECK(html.find("<section id=\"gap\">") != std::string::npos);
  CHECK(html.find("@media print") != std::string::npos);
  CHECK(test::xml_problem(html.substr(html.find("<body>"), html.find("</body>") + 7 - html.find("<body>"))) == "");
}

TEST_CASE("report html: names are escaped, parameters with units and bounds, err per data set") {
  const std::string html = runtime::report::html_report(sample_content());
  CHECK(html.find("dir/&lt;odd&gt; &amp; name.rheo") != std::string::npos);
  CHECK(html.find("<odd>") == std::string::npos);
  CHECK(html.find("<td><code>k.k</code></td><td class=\"num\">100</td><td>N/mm</td><td>[1, 1000]</td>") != std::string::npos);
  CHECK(html.find("N*s/mm") != std::string::npos);
  CHECK(html.find("err (6.1) = ") != std::string::npos);
  CHECK(html.find("force residual RMS 1 %, worst 2 %") != std::string::npos);
}

TEST_CASE("report html: a baseline (the model before a diagnosis) adds dashed curves and its residual maps on the same colour scale") {
  runtime::report::ReportContent content = sample_content();
  runtime::report::HarmonicComparison& grid = content.harmonic.front();
  for (std::size_t i = 0; i < grid.amplitude.size(); ++i) {
    grid.baseline_stiffness.push_back(0.9 * grid.measured_stiffness[i]);  // 10 % soft: the before map spans -10 %
    grid.baseline_phase.push_back(grid.measured_phase[i] - 0.05);
  }
  grid.baseline_err = 0.07;
  content.histories.front().baseline_force = {0, 80, 0, -80, 0};
  content.histories.front().baseline_rms = 0.12;
  content.baseline = "model kv as given, fitted";
  const std::string html = runtime::report::html_report(content);
  CHECK(count(html, "<figure") == 12);  // and the two maps of the baseline
  for (const char* kind : {"residual-stiffness-before", "residual-phase-before"}) CHECK(count(html, fmt::format("data-figure=\"{}\"", kind)) == 1);
  // Per curve a dashed twin: 3 amplitudes x 4 plots + 4 frequencies x 2 plots, and one loop.
  CHECK(count(html, "data-style=\"dashed\"") == 4 * 3 + 2 * 4 + 1);
  CHECK(count(html, "class=\"cell\"") == 4 * 12);
  CHECK(html.find("Dashed curves: model kv as given, fitted.") != std::string::npos);
  CHECK(html.find("(model before: 7.0000e-02)") != std::string::npos);
  CHECK(html.find("(model before: RMS 12 %)") != std::string::npos);
  // Both stiffness maps end their colour scale at 10 % (the baseline's largest residual), so
  // the refined model's 1 % cells are pale where the baseline's are saturated.
  const auto maps = runtime::report::residual_maps(grid);
  REQUIRE(maps.size() == 4);
  CHECK(maps[0].limit == doctest::Approx(10.0));
  CHECK(maps[2].limit == doctest::Approx(10.0));
  CHECK(maps[1].limit == maps[3].limit);
  CHECK(maps[2].title.find("before") != std::string::npos);
  CHECK(test::xml_problem(html.substr(html.find("<body>"), html.find("</body>") + 7 - html.find("<body>"))) == "");
}

TEST_CASE("report html: material data name their geometry and are drawn as moduli over strain") {
  runtime::report::ReportContent content = sample_content();
  runtime::report::HarmonicComparison& grid = content.harmonic.front();
  grid.source = {"Amplitude sweep", true, 490.874, 2.0};
  const std::string html = runtime::report::html_report(content);
  CHECK(html.find("TRIOS step &quot;Amplitude sweep&quot;") != std::string::npos);
  CHECK(html.find("area A = 490.874 mm^2, height h = 2 mm") != std::string::npos);
  CHECK(html.find("storage modulus E&#39; = K&#39;h/A [MPa]") != std::string::npos);
  CHECK(count(html, "class=\"meta source\"") == 1);
  // Strain only (a height, no area): no modulus, and the note says only what was converted.
  grid.source = {"", true, std::nullopt, 2.0};
  const std::string strain_only = runtime::report::html_report(content);
  CHECK(strain_only.find("height h = 2 mm: amplitude = strain x h") != std::string::npos);
  CHECK(strain_only.find("modulus x A") == std::string::npos);
  CHECK(strain_only.find("[MPa]") == std::string::npos);
}

TEST_CASE("report html: a history from a preloaded start says the model starts relaxed there, and names the force offset it was shown with") {
  runtime::report::ReportContent content = sample_content();
  CHECK(runtime::report::html_report(content).find("starts relaxed") == std::string::npos);  // from 0: nothing to say
  runtime::report::HistoryComparison& loop = content.histories.front();
  loop.displacement = {2.0, 2.5, 2.0, 1.5, 2.0};
  loop.offset = {true, true, 0.0};
  loop.offset_value = 151.25;
  const std::string html = runtime::report::html_report(content);
  CHECK(html.find("The model starts relaxed at the first sample&#39;s displacement, 2 mm") != std::string::npos);
  CHECK(html.find("load cell&#39;s offset, 151.25 N (force_offset = free: fitted)") != std::string::npos);
  loop.offset = {true, false, 150.0};
  loop.offset_value = 150.0;
  CHECK(runtime::report::html_report(content).find("150 N (force_offset as declared on the data line)") != std::string::npos);
}

}  // namespace html_report_test
