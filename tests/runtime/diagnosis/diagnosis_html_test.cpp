// The report of rheo diagnose / refine on static loops behind which a Yeoh law hides (the
// hidden-effects case, diagnosis_hidden_effects_test.cpp): the refined model drawn with the
// model before as its baseline, the gap table, the candidates and the added lines.
#include "runtime/diagnosis/diagnosis_html.hpp"

#include "diagnosis_support.hpp"
#include "report_support.hpp"
#include "runtime/protocols/run_history.hpp"
#include "runtime/report/html_report.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <stdexcept>

namespace diagnosis_html_test {

using namespace rheo;
namespace dx = runtime::diagnosis;
using test::count;

namespace {

const std::string kStart =
    "model start {\n  spring r (k = 300 N/mm in [10, 10000])\n  friction f (k = 100 N/mm in [1, 10000], uy = 20 um in [0.1, 10000])\n}\n";

std::vector<runtime::FitDataSet> yeoh_loops() {
  const std::string truth = "model truth { yeoh r (D10 = 150 N/mm, D20 = -1 N/mm^3, D30 = 0.05 N/mm^5)  friction f (k = 200 N/mm, uy = 50 um) }";
  return {test::history_measurement(truth, runtime::static_triangle({5.0, 2.5, 1.0}, 0.05, 1, 400), 9)};
}

const runtime::FitDescription kDescription{"start.rheo", "exact", "phi", "default", 1};

std::string section_of(const runtime::report::ReportContent& content) {
  REQUIRE(content.sections.size() == 1);
  CHECK(content.sections.front().id == "diagnosis");
  return content.sections.front().html;
}

}  // namespace

TEST_CASE("diagnosis html: one round draws the refined model over the model before, the gap, the candidates and the added lines") {
  const auto data = yeoh_loops();
  const dx::Diagnosis d = test::diagnose(kStart, data, true);
  REQUIRE(d.effect == dx::Effect::nonlinear_elasticity);
  const runtime::report::ReportContent content = dx::diagnosis_report_content({d}, data, kDescription, "rheo diagnose");
  CHECK(content.title == "rheo diagnose: model start");
  CHECK(content.sections.front().title == "Diagnosis");
  // The refined network (a yeoh in place of the spring) with its fitted values and standard errors.
  CHECK(content.network.children.front().kind == lang::ElementKind::yeoh);
  int with_error = 0;
  for (const auto& row : content.parameters) with_error += row.free && row.standard_error.find('%') != std::string::npos;
  CHECK(with_error == static_cast<int>(d.after->free.size()));
  // The model before, at the same samples, with its own residual.
  REQUIRE(content.histories.size() == 1);
  const auto& loops = content.histories.front();
  CHECK(loops.baseline_force.size() == loops.model_force.size());
  CHECK(loops.baseline_rms == doctest::Approx(d.gap_before).scale(0.0));
  CHECK(loops.rms == doctest::Approx(d.gap_after).scale(0.0));
  CHECK(!content.baseline.empty());

  const std::string html = section_of(content);
  CHECK(html.find("<td>as given, fitted</td>") != std::string::npos);
  CHECK(html.find(fmt::format("<td>round 1: <code>r</code> added (nonlinear-elasticity)</td><td class=\"num\">{:.4g}</td>", d.gap_after)) !=
        std::string::npos);
  CHECK(count(html, "<tr class=\"chosen\">") == 1);
  CHECK(count(html, "<td>amplitude-dependence</td>") == 1);  // every screened effect has a row
  CHECK(count(html, "<td>rate-dependence</td>") == 1);
  CHECK(html.find("<pre><code>yeoh r (D10 = ") != std::string::npos);
  CHECK(count(html, "data-figure=\"network-before\"") == 1);
  const std::string page = runtime::report::html_report(content);
  CHECK(test::xml_problem(page.substr(page.find("<body>"), page.find("</body>") + 7 - page.find("<body>"))) == "");
  CHECK(count(page, "data-style=\"dashed\"") == 1);  // the loop of the model before
}

TEST_CASE("diagnosis html: refine's rounds each get a row and a part, a last round of none adds nothing to draw") {
  const auto data = yeoh_loops();
  const dx::Diagnosis first = test::diagnose(kStart, data);
  REQUIRE(first.effect == dx::Effect::nonlinear_elasticity);
  const dx::Diagnosis second = test::diagnose(first.refined_text, data);
  const runtime::report::ReportContent content = dx::diagnosis_report_content({first, second}, data, kDescription, "rheo refine");
  CHECK(content.title == "rheo refine: model start");
  CHECK(content.sections.front().title == "Refinement");
  const std::string html = section_of(content);
  CHECK(html.find("<h3>Round 1: nonlinear-elasticity</h3>") != std::string::npos);
  CHECK(html.find(fmt::format("<h3>Round 2: {}</h3>", dx::effect_name(second.effect))) != std::string::npos);
  CHECK(html.find("<td>round 2: ") != std::string::npos);
  // The baseline is the model before the first round, the drawn model the last round's.
  CHECK(content.histories.front().baseline_rms == doctest::Approx(first.gap_before).scale(0.0));
  CHECK(content.histories.front().rms == doctest::Approx(second.gap_after).scale(0.0));
}

TEST_CASE("diagnosis html: none draws the model as fitted, without a baseline, and says nothing was added") {
  const std::string truth = "model truth { spring s (k = 250 N/mm)  friction f (k = 300 N/mm, uy = 80 um) }";
  const std::vector<runtime::FitDataSet> data{test::history_measurement(truth, runtime::static_triangle({3.0, 1.0, 0.3}, 0.05, 1, 400), 12)};
  const dx::Diagnosis d = test::diagnose(kStart, data);
  REQUIRE(d.effect == dx::Effect::none);
  const runtime::report::ReportContent content = dx::diagnosis_report_content({d}, data, kDescription, "rheo diagnose");
  CHECK(content.baseline.empty());
  CHECK(content.histories.front().baseline_force.empty());
  const std::string html = section_of(content);
  CHECK(html.find("<td>round 1: nothing added (none)</td>") != std::string::npos);
  CHECK(html.find("<p>Nothing added.</p>") != std::string::npos);
  CHECK(html.find("network-before") == std::string::npos);
  CHECK_THROWS_AS(dx::diagnosis_report_content({}, data, kDescription, "rheo diagnose"), std::logic_error);
}

}  // namespace diagnosis_html_test
