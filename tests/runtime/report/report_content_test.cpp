#include "runtime/core/errors.hpp"
#include "runtime/io/output.hpp"
#include "runtime/report/report_content.hpp"
#include "runtime/report/svg_text.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace report_content_test {

using namespace rheo;

namespace {
std::vector<runtime::HarmonicPoint> two_points() {
  std::vector<runtime::HarmonicPoint> points(2);
  points[0].amplitude = 0.2, points[0].frequency = 1.0, points[0].measures.stiffness = 110.0, points[0].measures.phase = 0.1;
  points[1].amplitude = 0.2, points[1].frequency = 5.0, points[1].measures.stiffness = 90.0, points[1].measures.phase = 0.2;
  return points;
}
}  // namespace

TEST_CASE("report content: simulate results are drawn from their data, phase in radians") {
  const runtime::ResultHeader header{"m", "m.rheo", "harmonic"};
  runtime::report::ReportContent content;
  runtime::report::add_simulation_result(content, "grid", {header, runtime::HarmonicGrid{two_points(), runtime::HarmonicDefinition::thesis}, 0, ""});
  REQUIRE(content.harmonic.size() == 1);
  const auto& h = content.harmonic.front();
  CHECK(h.label == "grid");
  CHECK_FALSE(h.measured());
  CHECK(h.amplitude == std::vector<double>{0.2, 0.2});
  CHECK(h.frequency == std::vector<double>{1.0, 5.0});
  CHECK(h.model_stiffness == std::vector<double>{110.0, 90.0});
  CHECK(h.model_phase == std::vector<double>{0.1, 0.2});

  const runtime::History history{{0.0, 1.0, 2.0}, {0.0, 0.5, 0.0}, {0.0, 50.0, 10.0}, {}, {}, {}};
  runtime::report::add_simulation_result(content, "loop", {header, history, 0, ""});
  REQUIRE(content.histories.size() == 1);
  CHECK(content.histories.front().displacement == std::vector<double>{0.0, 0.5, 0.0});
  CHECK(content.histories.front().model_force == std::vector<double>{0.0, 50.0, 10.0});
  CHECK_FALSE(content.histories.front().measured());
}

TEST_CASE("report content: residuals of a harmonic grid and of a history") {
  runtime::HarmonicData data;
  data.path = "grid.csv";
  data.amplitude = {0.2, 0.2}, data.frequency = {1.0, 5.0}, data.stiffness = {100.0, 100.0}, data.phase = {0.1, 0.2};
  const auto h = runtime::report::compare_harmonic(data, two_points());
  CHECK(h.measured());
  CHECK(h.phi == doctest::Approx(0.01 + 0.01).scale(0.0));  // stiffness +10 % and -10 %, damping exact
  CHECK(h.err == doctest::Approx(std::sqrt(0.02) / 2).scale(0.0));

  runtime::HistoryData history;
  history.path = "loop.csv";
  history.drive = {{0.0, 1.0}, {0.0, 1.0}};
  history.force = {0.0, 200.0};
  history.force_scale = 200.0;
  const auto loop = runtime::report::compare_history(history, {10.0, 190.0});
  CHECK(loop.rms == doctest::Approx(0.05).scale(0.0));
  CHECK(loop.worst == doctest::Approx(0.05).scale(0.0));
}

TEST_CASE("report content: the model's parameters in the units written, with bounds") {
  const runtime::Network network = test::network_from("model m { maxwell m1 (k = 2 kN/mm in [1, 10], tau = 5 ms) }", "m");
  const auto content = runtime::report::report_for_model(network, "m.rheo", "rheo report");
  CHECK(content.title == "rheo report: model m");
  REQUIRE(content.parameters.size() >= 2);
  CHECK(content.parameters[0].path == "m1.k");
  CHECK(content.parameters[0].unit == "kN/mm");
  CHECK(content.parameters[0].value == doctest::Approx(2.0));
  CHECK(content.parameters[0].bounds == "[1, 10]");
  CHECK(runtime::report::escape("a&<>\"'") == "a&amp;&lt;&gt;&quot;&#39;");
}

}  // namespace report_content_test
