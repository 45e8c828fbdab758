#include "runtime/report/report_figures.hpp"
#include "runtime/core/errors.hpp"
#include "report_support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>

namespace report_figures_test {

using namespace rheo;
using runtime::report::HarmonicComparison;
using runtime::report::Plot;
using runtime::report::Scale;

namespace {

// The model of a Kelvin-Voigt element, stiffness K = |k + i w c|, at every (amplitude, frequency).
HarmonicComparison kelvin_voigt(const std::vector<double>& amplitudes, const std::vector<double>& frequencies, double k, double c) {
  HarmonicComparison g;
  for (const double a : amplitudes)
    for (const double f : frequencies) {
      const double w = 2 * std::numbers::pi * f;
      g.amplitude.push_back(a), g.frequency.push_back(f);
      g.model_stiffness.push_back(std::hypot(k, c * w)), g.model_phase.push_back(std::atan2(c * w, k));
    }
  return g;
}

std::vector<std::string> ids(const std::vector<Plot>& plots) {
  std::vector<std::string> out;
  for (const Plot& p : plots) out.push_back(p.id);
  return out;
}

}  // namespace

TEST_CASE("report figures: at most 8 curves, spread over the values, the primary figure is standalone") {
  HarmonicComparison grid;
  for (int a = 1; a <= 12; ++a)
    for (const double f : {1.0, 10.0}) {
      grid.amplitude.push_back(0.1 * a), grid.frequency.push_back(f);
      grid.model_stiffness.push_back(100.0), grid.model_phase.push_back(0.1);
    }
  const auto plots = runtime::report::harmonic_plots(grid, "x");
  CHECK(ids(plots) == std::vector<std::string>{"x-stiffness-frequency", "x-phase-frequency", "x-stiffness-amplitude", "x-phase-amplitude",
                                               "x-storage-frequency", "x-loss-frequency"});
  CHECK(plots[0].series.size() == 8);  // model only: one line per amplitude, 8 of 12
  CHECK(plots[0].series.front().group == "0.1 mm");
  CHECK(plots[0].series.back().group == "1.2 mm");
  CHECK(plots[2].series.size() == 2);  // one per frequency
  CHECK(runtime::report::residual_maps(grid).empty());
  runtime::report::ReportContent content;
  content.harmonic.push_back(grid);
  const std::string svg = runtime::report::primary_figure_svg(content);
  CHECK(svg.starts_with("<?xml"));
  CHECK(test::xml_problem(svg) == "");
  CHECK(svg.find("Dynamic stiffness over frequency") != std::string::npos);
  CHECK_THROWS_AS(runtime::report::primary_figure_svg(runtime::report::ReportContent{}), runtime::UsageError);
}

TEST_CASE("report figures: a master curve at one amplitude is drawn over frequency only, stiffness on a log axis") {
  std::vector<double> frequencies;
  for (int e = -14; e <= 6; ++e)  // 20 decades; K' = K cos(phase) keeps its digits to about 1e6 Hz
    frequencies.push_back(std::pow(10.0, e));
  const HarmonicComparison g = kelvin_voigt({0.1}, frequencies, 50.0, 1.0);
  const auto axes = runtime::report::harmonic_axes(g);
  CHECK(axes.over_frequency);
  CHECK_FALSE(axes.over_amplitude);
  const auto plots = runtime::report::harmonic_plots(g, "m");
  CHECK(ids(plots) == std::vector<std::string>{"m-stiffness-frequency", "m-phase-frequency", "m-storage-frequency", "m-loss-frequency"});
  CHECK(plots[0].x.scale == Scale::log);
  CHECK(plots[0].y.scale == Scale::log);  // 50 .. 6e6 N/mm
  CHECK(plots[1].y.scale == Scale::linear);
  CHECK(plots[2].y.scale == Scale::linear);  // K' = k throughout: no span
  CHECK(plots[3].y.scale == Scale::log);     // K'' = c w
  // K' = K cos(phase), K'' = K sin(phase) of the model at each point.
  REQUIRE(plots[3].series.size() == 1);
  for (std::size_t i = 0; i < frequencies.size(); ++i) {
    CHECK(plots[2].series[0].y[i] == doctest::Approx(50.0));
    CHECK(plots[3].series[0].y[i] == doctest::Approx(2 * std::numbers::pi * frequencies[i]).scale(0.0));
  }
}

TEST_CASE("report figures: an amplitude sweep at one frequency is drawn over amplitude, material data as moduli over strain") {
  HarmonicComparison g = kelvin_voigt({0.001, 0.01, 0.1, 1.0}, {1.0}, 2.0, 0.05);
  for (std::size_t i = 0; i < g.amplitude.size(); ++i) {  // measured softening with amplitude
    g.measured_stiffness.push_back(g.model_stiffness[i] / (1.0 + 10.0 * g.amplitude[i]));
    g.measured_phase.push_back(g.model_phase[i]);
  }
  auto plots = runtime::report::harmonic_plots(g, "a");
  CHECK(ids(plots) == std::vector<std::string>{"a-stiffness-amplitude", "a-phase-amplitude", "a-storage-amplitude", "a-loss-amplitude"});
  CHECK(plots[0].x.label == "amplitude [mm]");
  CHECK(plots[0].x.scale == Scale::log);
  CHECK(plots[0].series.size() == 2);  // one frequency: measured and model
  CHECK(plots[0].series[0].group == "1 Hz");
  CHECK(plots[2].y.label == "storage stiffness K' [N/mm]");

  g.source = {"Amplitude sweep", true, 400.0, 2.0};
  plots = runtime::report::harmonic_plots(g, "a");
  CHECK(plots[0].x.label == "amplitude [mm]");  // stiffness and phase as fitted
  CHECK(plots[2].x.label == "strain [%]");
  CHECK(plots[2].y.label == "storage modulus E' = K'h/A [MPa]");
  CHECK(plots[3].y.label == "loss modulus E'' = K''h/A [MPa]");
  const auto& measured = plots[2].series.at(0);
  REQUIRE(measured.style == runtime::report::SeriesStyle::markers);
  for (std::size_t i = 0; i < g.amplitude.size(); ++i) {
    CHECK(measured.x[i] == doctest::Approx(100.0 * g.amplitude[i] / 2.0).scale(0.0));
    CHECK(measured.y[i] == doctest::Approx(g.measured_stiffness[i] * std::cos(g.measured_phase[i]) * 2.0 / 400.0).scale(0.0));
  }
  runtime::report::ReportContent content;
  content.harmonic.push_back(g);
  CHECK(runtime::report::primary_figure_svg(content).find("Dynamic stiffness over amplitude") != std::string::npos);
}

TEST_CASE("report figures: the stiffness axis is linear over a narrow range and log over a wide one") {
  const auto narrow = runtime::report::harmonic_plots(kelvin_voigt({0.1, 1.0}, {1.0, 10.0}, 100.0, 0.1), "n");
  CHECK(narrow[0].y.scale == Scale::linear);
  const auto wide = runtime::report::harmonic_plots(kelvin_voigt({0.1, 1.0}, {1.0, 1000.0}, 10.0, 1.0), "w");
  CHECK(wide[0].y.scale == Scale::log);
  CHECK(wide[1].y.scale == Scale::linear);  // phase never
}

}  // namespace report_figures_test
