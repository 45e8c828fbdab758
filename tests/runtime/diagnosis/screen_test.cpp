#include "runtime/diagnosis/screen.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <numbers>

namespace screen_test {

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
  const auto screened = dx::screen(fit, data, score, 0.1);
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

namespace {

runtime::HarmonicOptions exact_cycles() {
  runtime::HarmonicOptions o;
  o.steps_per_cycle = 256;
  o.solver = runtime::SolverChoice::fixed;
  o.tolerance = 1e-6;
  return o;
}

// The fit of MODEL as the screen reads it (its predictions on the grid, nothing fitted), and the
// noise-free table of TRUTH on the same grid.
std::pair<runtime::FitResult, std::vector<runtime::FitDataSet>> grid_of(const std::string& model, const std::string& truth,
                                                                        const std::vector<double>& amplitudes,
                                                                        const std::vector<double>& frequencies) {
  runtime::FitResult fit{test::network_from(model, "m")};
  runtime::DataSetFit set;
  set.prediction.points = runtime::simulate_harmonic_grid(fit.network, amplitudes, frequencies, exact_cycles());
  fit.datasets.push_back(set);
  runtime::HarmonicData d;
  d.path = "grid.csv";
  for (const auto& p : runtime::simulate_harmonic_grid(test::network_from(truth, "truth"), amplitudes, frequencies, exact_cycles())) {
    d.amplitude.push_back(p.amplitude), d.frequency.push_back(p.frequency);
    d.stiffness.push_back(p.measures.stiffness), d.phase.push_back(p.measures.phase);
    d.rows.push_back(static_cast<int>(d.rows.size()) + 2);
  }
  return {fit, {{d.path, 1.0, d}}};
}

}  // namespace

// Free play closing only at the top amplitude, behind a spring ten times the measured stiffness:
// the screen adds the trial's K* to the model's (close for a branch in parallel: their forces
// add), so the spring behind the true play removes nearly the whole objective. Its half-width (1.7 mm) lies between the two
// largest amplitudes (1.6, 2 mm), where a unit spring engages for g = 0.068 of its k at 2 mm
// (symmetric play: g = 1 - (2/pi)(asin(h/a) + (h/a) sqrt(1 - (h/a)^2))): the trial's k was
// bounded by 3 times the measured stiffness (~300 N/mm) and could add no more than 94 N/mm of the
// 204 there (gain ~0.7); it is now bounded by what it adds where it engages most.
TEST_CASE("diagnosis screen: a stiff spring behind play that closes only at the top amplitude is sized past the measured stiffness") {
  const char* model = "model m { spring s (k = 300 N/mm in [10, 10000])  maxwell r (k = 80 N/mm in [1, 10000], tau = 5 ms in [0.01, 10000]) }";
  const std::string truth =
      "model truth { spring s (k = 300 N/mm)  maxwell r (k = 80 N/mm, tau = 5 ms)  series b { gap g (width = 3.4 mm)  spring k (k = 3000 N/mm) } }";
  const auto [fit, data] = grid_of(model, truth, {0.1, 0.3, 1.0, 1.6, 2.0}, {1.0, 10.0});
  runtime::ScoreSettings score;
  score.harmonic = exact_cycles();
  const auto screened = dx::screen(fit, data, score, 0.1);
  const dx::ScreenedEffect* play = nullptr;
  for (const auto& s : screened)
    if (s.effect == dx::Effect::backlash) play = &s;
  REQUIRE(play);
  INFO(dx::trial_summary(play->trial), ", gain ", play->gain);
  CHECK(play->gain > 0.95);
  CHECK(play->trial.shape == dx::Shape::gapped_spring);
  // It closes between the two largest amplitudes (at slip (1 - |bias|) on its nearer side).
  CHECK(play->trial.slip * (1.0 - std::abs(play->trial.bias)) > 1.6);
  CHECK(play->trial.slip * (1.0 - std::abs(play->trial.bias)) < 2.0);
}

}  // namespace screen_test
