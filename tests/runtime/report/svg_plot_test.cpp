#include "runtime/report/residual_map.hpp"
#include "runtime/report/svg_plot.hpp"
#include "report_support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <cstring>
#include <limits>

namespace svg_plot_test {

using namespace rheo::runtime::report;
using rheo::test::count;
using rheo::test::xml_problem;

namespace {
Plot two_groups() {
  Plot plot{"p1", "Dynamic stiffness over frequency", {"frequency [Hz]", Scale::log}, {"dynamic stiffness [N/mm]", Scale::linear}, {}};
  plot.series.push_back({"0.2 mm measured", "0.2 mm", 0, SeriesStyle::markers, {1, 10, 100}, {1400, 1450, 1500}});
  plot.series.push_back({"0.2 mm model", "0.2 mm", 0, SeriesStyle::line, {1, 10, 100}, {1410, 1440, 1510}});
  plot.series.push_back({"1 mm model", "1 mm", 1, SeriesStyle::line, {1, 10, 100}, {1000, 1050, 1100}});
  return plot;
}
}  // namespace

TEST_CASE("report svg plot: one group element per series, well-formed, labelled axes and legend") {
  const std::string svg = render_svg(two_groups(), true);
  CHECK(xml_problem(svg) == "");
  CHECK(count(svg, "class=\"series\"") == 3);
  CHECK(count(svg, "data-style=\"markers\"") == 1);
  CHECK(count(svg, "data-style=\"line\"") == 2);
  CHECK(svg.find("frequency [Hz] (log)") != std::string::npos);
  CHECK(svg.find("dynamic stiffness [N/mm]") != std::string::npos);
  CHECK(svg.find(">100<") != std::string::npos);  // a decade tick of the log axis
  CHECK(svg.find("markers: measured") != std::string::npos);
  CHECK(svg.find("xmlns=\"http://www.w3.org/2000/svg\"") != std::string::npos);
  const std::string inline_svg = render_svg(two_groups(), false);
  CHECK(inline_svg.find("http") == std::string::npos);
  CHECK(inline_svg.find("<?xml") == std::string::npos);
}

TEST_CASE("report svg plot: a dashed series (the model before) is drawn dashed and the legend says what each style means") {
  Plot plot = two_groups();
  plot.series.push_back({"0.2 mm model before", "0.2 mm", 0, SeriesStyle::dashed, {1, 10, 100}, {1300, 1350, 1400}});
  plot.meaning[1] = "refined";
  const std::string svg = render_svg(plot, true);
  CHECK(xml_problem(svg) == "");
  CHECK(count(svg, "data-style=\"dashed\"") == 1);
  const auto dashed = svg.find("data-style=\"dashed\"");
  CHECK(svg.substr(dashed, svg.find("</g>", dashed) - dashed).find("stroke-dasharray") != std::string::npos);
  CHECK(svg.find("markers: measured") != std::string::npos);
  CHECK(svg.find("line: refined") != std::string::npos);
  CHECK(svg.find("dashed: before") != std::string::npos);
  // Without a dashed series the key names only the styles present.
  CHECK(render_svg(two_groups(), true).find("dashed:") == std::string::npos);
}

TEST_CASE("report svg plot: names are escaped and non-finite points break a line") {
  Plot plot{"p2", "a <b> & \"c\"", {"x [-]", Scale::linear}, {"y [-]", Scale::linear}, {}};
  const double nan = std::numeric_limits<double>::quiet_NaN();
  plot.series.push_back({"<script>alert('x')</script>", "g & h", 0, SeriesStyle::line, {0, 1, 2, 3}, {0, 1, nan, 3}});
  const std::string svg = render_svg(plot, true);
  CHECK(xml_problem(svg) == "");
  CHECK(svg.find("<script") == std::string::npos);
  CHECK(svg.find("&lt;script&gt;alert(&#39;x&#39;)") != std::string::npos);
  CHECK(svg.find("g &amp; h") != std::string::npos);
  // Two pieces: the line restarts (M) after the NaN.
  const auto d = svg.find("d=\"M", svg.find("class=\"series\""));
  const auto end = svg.find('"', d + 3);
  CHECK(count(svg.substr(d, end - d), "M") == 2);
}

TEST_CASE("report svg plot: log scale only for positive values spanning a factor of 20") {
  CHECK(scale_for({1, 3, 51}) == Scale::log);
  CHECK(scale_for({1, 3, 19}) == Scale::linear);
  CHECK(scale_for({0, 3, 100}) == Scale::linear);
  CHECK(scale_for({0.1, 0.5, 2.0}) == Scale::log);
}

TEST_CASE("report residual map: a cell per point on a symmetric diverging scale") {
  ResidualMap map{"Stiffness residual", "%", {0.2, 0.2, 1.0, 1.0}, {1, 5, 1, 5}, {0.0, 1.3, -0.4, 0.7}};
  const std::string svg = render_residual_map(map, true);
  CHECK(xml_problem(svg) == "");
  CHECK(count(svg, "class=\"cell\"") == 4);
  CHECK(color_scale_limit(map.value) == doctest::Approx(2.0));
  CHECK(color_scale_limit({0.0, 0.0}) == doctest::Approx(1.0));
  CHECK(color_scale_limit({-0.05}) == doctest::Approx(0.05).scale(0.0));
  CHECK(diverging_color(0.0, 1.0) == "#f7f7f7");
  CHECK(diverging_color(1.0, 1.0) == "#b2182b");
  CHECK(diverging_color(-5.0, 1.0) == "#2166ac");  // clamped
  CHECK(svg.find("+2") != std::string::npos);      // the scale's ends are labelled
  CHECK(svg.find("amplitude [mm]") != std::string::npos);
}

namespace {
struct Label {
  double x = 0, y = 0;
  std::string text;
};

// The tick labels of a rendered plot with the given text-anchor ("middle": the x axis, "end": the y axis).
std::vector<Label> tick_labels(const std::string& svg, const std::string& anchor) {
  std::vector<Label> out;
  const std::size_t group = svg.find("<g class=\"tick-labels\"");
  const std::size_t end = svg.find("</g>", group);
  for (std::size_t at = svg.find("<text ", group); at < end; at = svg.find("<text ", at + 1)) {
    const std::string tag = svg.substr(at, svg.find('>', at) - at);
    if (tag.find("text-anchor=\"" + anchor + "\"") == std::string::npos) continue;
    const auto attribute = [&](const char* name) { return std::stod(tag.substr(tag.find(name) + std::strlen(name))); };
    const std::size_t text = svg.find('>', at) + 1;
    out.push_back({attribute(" x=\""), attribute(" y=\""), svg.substr(text, svg.find('<', text) - text)});
  }
  return out;
}
}  // namespace

TEST_CASE("report svg plot: 28 decades of frequency and 16 of stiffness, labels compact and apart") {
  Plot plot{"wide", "Master curve", {"frequency [Hz]", Scale::log}, {"dynamic stiffness [N/mm]", Scale::log}, {}};
  Series s{"model", "0.1 mm", 0, SeriesStyle::line, {}, {}};
  for (int e = -14; e <= 14; ++e) s.x.push_back(std::pow(10.0, e)), s.y.push_back(50.0 * std::pow(10.0, 0.6 * (e + 14)));
  plot.series.push_back(s);
  const std::string svg = render_svg(plot, true);
  CHECK(xml_problem(svg) == "");
  const std::vector<Label> x = tick_labels(svg, "middle"), y = tick_labels(svg, "end");
  CHECK(x.size() >= 4);
  CHECK(x.size() <= 8);
  CHECK(y.size() >= 3);
  // 7.5 units a character at font size 13 is generous for digits: neighbours must not touch.
  for (std::size_t i = 1; i < x.size(); ++i) {
    CAPTURE(x[i].text);
    CHECK(x[i].x - x[i - 1].x > 7.5 * static_cast<double>(x[i].text.size() + x[i - 1].text.size()) / 2 + 4);
  }
  for (std::size_t i = 1; i < y.size(); ++i) CHECK(std::abs(y[i].y - y[i - 1].y) > 16);
  for (const auto& labels : {x, y})
    for (const Label& l : labels) {
      CAPTURE(l.text);
      CHECK(l.text.size() <= 5);
      CHECK(l.text.find('+') == std::string::npos);
    }
  // Every decade has a grid line, labelled or not.
  CHECK(count(svg, "stroke=\"#eeeeee\"") + x.size() + y.size() >= 29 + 15);
}

TEST_CASE("report svg plot: on a log axis the markers set the range, a line far below them is clipped a decade beyond") {
  Plot plot{"clip", "Storage", {"strain [%]", Scale::log}, {"storage modulus [MPa]", Scale::log}, {}};
  plot.series.push_back({"measured", "1 Hz", 0, SeriesStyle::markers, {0.01, 1, 100}, {0.02, 0.01, 0.001}});
  plot.series.push_back({"model", "1 Hz", 0, SeriesStyle::line, {0.01, 1, 100}, {0.02, 0.01, 1e-18}});
  const std::vector<Label> y = tick_labels(render_svg(plot, true), "end");
  REQUIRE(!y.empty());
  for (const Label& l : y) {
    CAPTURE(l.text);
    CHECK(std::stod(l.text) >= 1e-4);  // 0.001 / 10
    CHECK(std::stod(l.text) <= 0.2);   // 0.02 x 10
  }
  // Without markers the line's own range is drawn.
  plot.series.erase(plot.series.begin());
  bool deep = false;
  for (const Label& l : tick_labels(render_svg(plot, true), "end")) deep = deep || std::stod(l.text) < 1e-10;
  CHECK(deep);
}

}  // namespace svg_plot_test
