#include "runtime/diagnosis/screen.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <numbers>

using namespace rheo;
namespace dx = runtime::diagnosis;

TEST_CASE("diagnosis screen: a Maxwell element missing from a linear model is found with its k and tau (closed form data)") {
  // Data: K* = 500 + 200 i w tau / (1 + i w tau), tau = 5 ms, exact. Model: the spring alone.
  // Linear elements superpose exactly, so the best Maxwell trial must remove (almost) all of the
  // objective and land near k = 200 N/mm, tau = 5 ms (the pattern search's last step is 2^(1/4)).
  const double k = 200.0, tau = 0.005;
  runtime::HarmonicData d;
  d.path = "maxwell.csv";
  runtime::FitResult fit{test::network_from("model m { spring s (k = 500 N/mm in [1, 10000]) }", "m")};
  runtime::DataSetFit set;
  for (double a : {0.1, 1.0})
    for (double f : {1.0, 5.0, 20.0, 60.0}) {
      const std::complex<double> iwt(0.0, 2.0 * std::numbers::pi * f * tau);
      const std::complex<double> measured = 500.0 + k * iwt / (1.0 + iwt);
      d.amplitude.push_back(a), d.frequency.push_back(f), d.stiffness.push_back(std::abs(measured)), d.phase.push_back(std::arg(measured));
      runtime::HarmonicPoint p;
      p.amplitude = a, p.frequency = f, p.measures.stiffness = 500.0, p.measures.phase = 0.0;
      set.prediction.points.push_back(p);
    }
  fit.datasets.push_back(set);
  const std::vector<runtime::FitDataSet> data{{d.path, 1.0, d}};
  runtime::ScoreSettings score;
  score.harmonic.steps_per_cycle = 128;
  score.harmonic.solver = runtime::SolverChoice::fixed;
  score.harmonic.tolerance = 1e-6;
  const auto screened = dx::screen(fit, data, score);
  REQUIRE(!screened.empty());
  const dx::ScreenedEffect* rate = nullptr;
  for (const auto& s : screened)
    if (s.effect == dx::Effect::rate_dependence) rate = &s;
  REQUIRE(rate);
  CHECK(rate->gain > 0.99);
  CHECK(rate->trial.stiffness == doctest::Approx(k).epsilon(0.1));
  CHECK(rate->trial.time == doctest::Approx(tau).epsilon(0.1).scale(0.0));
  // A friction element has no rate dependence: it explains far less.
  for (const auto& s : screened)
    if (s.effect == dx::Effect::amplitude_dependence) CHECK(s.gain < rate->gain);
}

TEST_CASE("diagnosis screen: the data scales span the measured grid and a history's turning points") {
  runtime::HarmonicData d;
  d.amplitude = {0.1, 2.0}, d.frequency = {1.0, 40.0}, d.stiffness = {100.0, 300.0}, d.phase = {0.1, 0.2};
  const dx::DataScales s = dx::data_scales({{"h.csv", 1.0, d}});
  CHECK(s.amplitude_low == 0.1);
  CHECK(s.amplitude_high == 2.0);
  CHECK(s.frequency_low == 1.0);
  CHECK(s.frequency_high == 40.0);
  CHECK(s.bounds.max_displacement == 2.0);
  CHECK((s.bounds.stiffness == 100.0 || s.bounds.stiffness == 300.0));
}
