#include "runtime/diagnosis/patterns.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace patterns_test {

using namespace rheo;

namespace {

const std::vector<double> kA{0.1, 0.5, 2.0};         // mm
const std::vector<double> kF{1.0, 5.0, 10.0, 40.0};  // Hz

// A fit whose stiffness residual on the kA x kF grid is r(i, j) (damping residual 0) and whose
// model phase is 1 deg above the measured 10 deg everywhere.
template <class R>
std::pair<runtime::FitResult, std::vector<runtime::FitDataSet>> fit_with(const R& r) {
  runtime::HarmonicData d;
  runtime::DataSetFit set;
  for (std::size_t i = 0; i < kA.size(); ++i)
    for (std::size_t j = 0; j < kF.size(); ++j) {
      d.amplitude.push_back(kA[i]), d.frequency.push_back(kF[j]), d.stiffness.push_back(100.0), d.phase.push_back(10.0 * std::numbers::pi / 180);
      runtime::HarmonicPoint p;
      p.amplitude = kA[i], p.frequency = kF[j], p.measures.phase = 11.0 * std::numbers::pi / 180;
      set.prediction.points.push_back(p);
      set.residuals.stiffness.push_back(r(i, j));
      set.residuals.damping.push_back(0.0);
    }
  runtime::FitResult fit{test::network_from("model m { spring s (k = 1 N/mm) }", "m")};
  fit.datasets.push_back(set);
  return {std::move(fit), {runtime::FitDataSet{"grid.csv", 1.0, d, {}}}};
}

}  // namespace

TEST_CASE("diagnosis patterns: orthogonal amplitude, frequency and interaction parts give their exact shares") {
  // A zero-mean over amplitudes, F zero-mean over frequencies, I = c s_i t_j with zero-sum s, t:
  // the parts are orthogonal, so their shares are SS_part / SS_total exactly.
  const std::vector<double> a{-0.02, 0.0, 0.02}, f{0.01, -0.01, 0.01, -0.01}, s{1.0, -2.0, 1.0}, t{1.0, 1.0, -1.0, -1.0};
  const double c = 0.005;
  auto [fit, data] = fit_with([&](std::size_t i, std::size_t j) { return a[i] + f[j] + c * s[i] * t[j]; });
  const auto p = runtime::diagnosis::residual_patterns(fit, data);
  double ss_a = 0, ss_f = 0, ss_i = 0;
  for (std::size_t i = 0; i < 3; ++i)
    for (std::size_t j = 0; j < 4; ++j) ss_a += a[i] * a[i], ss_f += f[j] * f[j], ss_i += c * c * s[i] * s[i] * t[j] * t[j];
  const double total = ss_a + ss_f + ss_i;
  REQUIRE(p.has_harmonic);
  CHECK(p.harmonic.amplitude_share == doctest::Approx(ss_a / total).epsilon(1e-9).scale(0.0));
  CHECK(p.harmonic.frequency_share == doctest::Approx(ss_f / total).epsilon(1e-9).scale(0.0));
  CHECK(p.harmonic.interaction_share == doctest::Approx(ss_i / total).epsilon(1e-9).scale(0.0));
  CHECK(p.harmonic.stiffness_rms == doctest::Approx(std::sqrt(total / 12)).epsilon(1e-12).scale(0.0));
  CHECK(test::degrees(p.harmonic.phase_rms) == doctest::Approx(1.0).epsilon(1e-12));
  CHECK(p.harmonic.worst_stiffness.residual == doctest::Approx(-0.02 - 0.01 - c).epsilon(1e-12).scale(0.0));  // i = 0, j = 3
  CHECK(p.harmonic.worst_stiffness.amplitude == 0.1);
  CHECK(p.harmonic.worst_stiffness.frequency == 40.0);
}

TEST_CASE("diagnosis patterns: a missing cell of the grid still splits an additive residual exactly") {
  auto [fit, data] = fit_with([](std::size_t i, std::size_t j) { return 0.01 * static_cast<double>(i) - 0.003 * static_cast<double>(j); });
  // Drop the last point: back-fitting still recovers the additive parts, so no interaction remains.
  auto& h = std::get<runtime::HarmonicData>(data.front().data);
  h.amplitude.pop_back(), h.frequency.pop_back(), h.stiffness.pop_back(), h.phase.pop_back();
  auto& set = fit.datasets.front();
  set.prediction.points.pop_back(), set.residuals.stiffness.pop_back(), set.residuals.damping.pop_back();
  const auto p = runtime::diagnosis::residual_patterns(fit, data);
  CHECK(p.harmonic.interaction_share < 1e-12);
  CHECK(p.harmonic.amplitude_share > p.harmonic.frequency_share);
}

TEST_CASE("diagnosis patterns: the interaction's degrees of freedom, (n_a - 1)(n_f - 1) on a grid, none on an L of two sweeps") {
  // Keeps the points of the 3 x 4 grid for which KEEP(i, j) holds.
  auto patterns_of = [](auto keep) {
    auto [fit, data] = fit_with([](std::size_t i, std::size_t j) { return 0.01 * static_cast<double>(i * j); });  // pure interaction
    auto& h = std::get<runtime::HarmonicData>(data.front().data);
    auto& set = fit.datasets.front();
    runtime::HarmonicData kept;
    runtime::DataSetFit kept_set;
    for (std::size_t k = 0; k < h.size(); ++k)
      if (keep(k / kF.size(), k % kF.size())) {
        kept.amplitude.push_back(h.amplitude[k]), kept.frequency.push_back(h.frequency[k]);
        kept.stiffness.push_back(h.stiffness[k]), kept.phase.push_back(h.phase[k]);
        kept_set.prediction.points.push_back(set.prediction.points[k]);
        kept_set.residuals.stiffness.push_back(set.residuals.stiffness[k]), kept_set.residuals.damping.push_back(0.0);
      }
    h = kept, set = kept_set;
    return runtime::diagnosis::residual_patterns(fit, data).harmonic;
  };
  const auto grid = patterns_of([](std::size_t, std::size_t) { return true; });
  CHECK(grid.interaction_dof == 6);
  CHECK(grid.interaction_measured());
  CHECK(grid.interaction_share > 0.1);
  // An amplitude sweep at 5 Hz and a frequency sweep at 0.5 mm: every residual is additive there.
  const auto l_shape = patterns_of([](std::size_t i, std::size_t j) { return i == 1 || j == 1; });
  CHECK(l_shape.interaction_dof == 0);
  CHECK_FALSE(l_shape.interaction_measured());
  CHECK(l_shape.interaction_share < 1e-12);
  // The L and one more point off both sweeps: one degree of freedom.
  const auto l_plus = patterns_of([](std::size_t i, std::size_t j) { return i == 1 || j == 1 || (i == 2 && j == 3); });
  CHECK(l_plus.interaction_dof == 1);
}

}  // namespace patterns_test
