// Scoring of a fit (runtime/fit/fit_scoring.hpp): the residual terms of each objective against hand
// values, the file and point weights, and the model response of each method against the
// modules it delegates to (and, for a linear network, the approximation against the exact
// response: the approximation is exact there).
#include "runtime/fit/fit_scoring.hpp"
#include "runtime/protocols/run_history.hpp"
#include "runtime/protocols/harmonic.hpp"

#include "runtime/fit/objective.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <stdexcept>

namespace fit_scoring_test {

using namespace rheo;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

// Measured: (100 N/mm, 10 deg) and (200 N/mm, 20 deg); the model gives (110, 12 deg) and (190, 18 deg).
runtime::FitDataSet two_point_table(double weight) {
  runtime::HarmonicData d;
  d.path = "two.csv";
  d.amplitude = {0.5, 1.0};
  d.frequency = {10.0, 20.0};
  d.stiffness = {100.0, 200.0};
  d.phase = {10.0 * deg, 20.0 * deg};
  d.rows = {3, 4};
  return {"two.csv", weight, d};
}

runtime::Prediction two_point_model() {
  runtime::Prediction p;
  const double stiffness[] = {110.0, 190.0}, phase[] = {12.0 * deg, 18.0 * deg};
  for (int i = 0; i < 2; ++i) {
    runtime::HarmonicPoint point;
    point.measures.stiffness = stiffness[i];
    point.measures.phase = phase[i];
    p.points.push_back(point);
  }
  return p;
}

// Measured force {0, 5, -10, 20} N (max |F| = 20 N), the model {1, 5, -8, 18} N.
runtime::FitDataSet four_sample_history(double weight) {
  runtime::HistoryData h;
  h.path = "h.csv";
  h.drive = {{0.0, 1.0, 2.0, 3.0}, {0.0, 0.1, -0.2, 0.4}};
  h.force = {0.0, 5.0, -10.0, 20.0};
  h.rows = {3, 4, 5, 6};
  h.force_scale = 20.0;
  return {"h.csv", weight, h};
}

std::vector<double> residuals_of(const runtime::FitDataSet& set, const runtime::Prediction& p, const runtime::ScoreSettings& s) {
  std::vector<double> r;
  runtime::append_residuals(set, p, s, r);
  return r;
}

double sum_of_squares(const std::vector<double>& r) {
  double s = 0.0;
  for (double v : r) s += v * v;
  return s;
}

void check_equal(const std::vector<double>& got, const std::vector<double>& want, double tolerance) {
  REQUIRE(got.size() == want.size());
  for (std::size_t i = 0; i < want.size(); ++i) {
    CAPTURE(i);
    CHECK(std::abs(got[i] - want[i]) <= tolerance);
  }
}

}  // namespace

TEST_CASE("phi residuals: sqrt(w / 2n) sqrt(k) (K/K_exp - 1) and sqrt(w / 2n) sqrt(1 - k) (d/d_exp - 1), eq. 5.38") {
  runtime::ScoreSettings s;
  s.stiffness_weight = 0.3;
  s.damping_weight = 0.7;
  const auto set = two_point_table(2.0);
  const auto r = residuals_of(set, two_point_model(), s);
  // sqrt(2/4) sqrt(0.3) 0.1; sqrt(2/4) sqrt(0.7) (sin 12/sin 10 - 1); the same for point 2
  // with -0.05 and (sin 18/sin 20 - 1). Computed independently (Python, double precision).
  check_equal(r, {0.038729833462074176, 0.11673354720623175, -0.019364916731037088, -0.05708706522003674}, 1e-15);
  // The sum of squares is w / (2n) times eq. 5.38 as objective.hpp computes it.
  const auto points = two_point_model().points;
  const double phi_538 = runtime::phi(runtime::relative_residuals(set.harmonic(), points), 0.3, 0.7);
  CHECK(sum_of_squares(r) == doctest::Approx(2.0 / 4.0 * phi_538).epsilon(1e-14).scale(0.0));
}

TEST_CASE("phi residuals with the default weights are those of eq. 5.1") {
  const auto set = two_point_table(1.0);
  const auto r = residuals_of(set, two_point_model(), {});
  const double phi_51 = runtime::phi(runtime::relative_residuals(set.harmonic(), two_point_model().points), 1.0, 1.0);
  CHECK(sum_of_squares(r) == doctest::Approx(phi_51 / 4.0).epsilon(1e-14).scale(0.0));
  CHECK(r[0] == doctest::Approx(0.1 / 2.0).epsilon(1e-14).scale(0.0));  // sqrt(1/4) (110/100 - 1)
}

TEST_CASE("least-squares residuals: the complex stiffness difference relative to |K*_exp|") {
  runtime::ScoreSettings s;
  s.objective = runtime::FitObjective::least_squares;
  const auto r = residuals_of(two_point_table(2.0), two_point_model(), s);
  // sqrt(1/2) Re, Im of (110 e^{i 12 deg} - 100 e^{i 10 deg}) / 100 and
  // (190 e^{i 18 deg} - 200 e^{i 20 deg}) / 200; the phi weights play no part.
  check_equal(r, {0.06445604130822924, 0.03892953914274548, -0.02558943802291534, -0.03426215103478525}, 1e-15);
  s.stiffness_weight = 0.1;
  CHECK(residuals_of(two_point_table(2.0), two_point_model(), s) == r);
}

TEST_CASE("history residuals: sqrt(w / m) (F - F_exp) / max|F_exp|, for either objective") {
  runtime::Prediction p;
  p.force = {1.0, 5.0, -8.0, 18.0};
  const double scale = std::sqrt(3.0 / 4.0) / 20.0;
  for (const auto objective : {runtime::FitObjective::phi, runtime::FitObjective::least_squares}) {
    runtime::ScoreSettings s;
    s.objective = objective;
    check_equal(residuals_of(four_sample_history(3.0), p, s), {scale * 1.0, 0.0, scale * 2.0, scale * -2.0}, 1e-15);
  }
}

TEST_CASE("a file's weight w makes its sum of squares w times the mean of its squared terms") {
  runtime::Prediction history_model;
  history_model.force = {1.0, 5.0, -8.0, 18.0};
  // Unweighted terms: history (F - F_exp)/20 = {0.05, 0, 0.1, -0.1}; harmonic phi terms
  // {0.1, sin12/sin10 - 1, -0.05, sin18/sin20 - 1}.
  const double history_mean = (0.05 * 0.05 + 0.1 * 0.1 + 0.1 * 0.1) / 4.0;
  const double a = std::sin(12.0 * deg) / std::sin(10.0 * deg) - 1.0, b = std::sin(18.0 * deg) / std::sin(20.0 * deg) - 1.0;
  const double harmonic_mean = (0.01 + a * a + 0.0025 + b * b) / 4.0;
  for (const double w : {0.0, 0.5, 1.0, 7.0}) {
    CAPTURE(w);
    CHECK(sum_of_squares(residuals_of(four_sample_history(w), history_model, {})) == doctest::Approx(w * history_mean).epsilon(1e-14));
    CHECK(sum_of_squares(residuals_of(two_point_table(w), two_point_model(), {})) == doctest::Approx(w * harmonic_mean).epsilon(1e-14));
  }
}

TEST_CASE("a harmonic table's weight column multiplies its point's squared terms") {
  auto set = two_point_table(1.0);
  std::get<runtime::HarmonicData>(set.data).weight = {1.0, 4.0};
  const auto plain = residuals_of(two_point_table(1.0), two_point_model(), {});
  const auto weighted = residuals_of(set, two_point_model(), {});
  check_equal(weighted, {plain[0], plain[1], 2.0 * plain[2], 2.0 * plain[3]}, 1e-15);
}

TEST_CASE("a harmonic table's terms spread over threads: in point order after what `out` held, the hand values on 1, 2 and 3 threads") {
  // The two points of two_point_table repeated 150 times (300 points, so each thread takes
  // several runs of them); each pair of terms is then the hand values above scaled by
  // sqrt(2 / 300) (the mean over the points).
  runtime::FitDataSet set = two_point_table(2.0);
  auto& d = std::get<runtime::HarmonicData>(set.data);
  runtime::Prediction p;
  const runtime::Prediction two = two_point_model();
  const runtime::HarmonicData base = d;
  d = {};
  d.path = base.path;
  for (int copy = 0; copy < 150; ++copy)
    for (std::size_t i = 0; i < 2; ++i) {
      d.amplitude.push_back(base.amplitude[i]);
      d.frequency.push_back(base.frequency[i]);
      d.stiffness.push_back(base.stiffness[i]);
      d.phase.push_back(base.phase[i]);
      d.rows.push_back(3 + static_cast<int>(d.rows.size()));
      p.points.push_back(two.points[i]);
    }
  const std::vector<double> hand = {0.038729833462074176, 0.11673354720623175, -0.019364916731037088, -0.05708706522003674};
  for (const runtime::FitObjective objective : {runtime::FitObjective::phi, runtime::FitObjective::least_squares}) {
    runtime::ScoreSettings s;
    s.objective = objective;
    s.stiffness_weight = 0.3;
    s.damping_weight = 0.7;
    const std::vector<double> one = residuals_of(two_point_table(2.0), two, s);
    if (objective == runtime::FitObjective::phi) check_equal(one, hand, 1e-15);
    for (const int threads : {1, 2, 3}) {
      CAPTURE(threads);
      s.harmonic.threads = threads;
      std::vector<double> r = {-1.0, -2.0};  // what `out` held stays in front
      runtime::append_residuals(set, p, s, r);
      REQUIRE(r.size() == 602);
      CHECK(r[0] == -1.0);
      CHECK(r[1] == -2.0);
      for (std::size_t k = 0; k < 600; ++k) {
        CAPTURE(k);
        CHECK(r[2 + k] == doctest::Approx(one[k % 4] * std::sqrt(2.0 / 300.0)).epsilon(1e-14).scale(0.0));
      }
    }
  }
}

TEST_CASE("predict: approximate and corrected are thesis_approximation's response, pointwise in data order") {
  const auto network = test::network_from(
      "model m { spring e (k = 400) maxwell v (k = 60, tau = 5 ms) friction f1 (k = 300, uy = 40 um) friction f2 (k = 80, uy = 150 um) }", "m");
  runtime::HarmonicData d;
  d.path = "grid.csv";
  d.amplitude = {0.02, 1.0, 0.1, 0.5};  // not a grid: pointwise pairs in file order
  d.frequency = {3.0, 40.0, 15.0, 1.0};
  d.stiffness = {1.0, 1.0, 1.0, 1.0};
  d.phase = {0.1, 0.1, 0.1, 0.1};
  d.rows = {3, 4, 5, 6};
  const runtime::FitDataSet set{"grid.csv", 1.0, d};
  const auto direct = runtime::approximate_harmonic(network, d.amplitude, d.frequency);
  const auto approximate = runtime::predict(network, set, runtime::FitMethod::approximate, {}, nullptr).points;
  REQUIRE(approximate.size() == direct.size());
  for (std::size_t i = 0; i < direct.size(); ++i) {
    CHECK(approximate[i].amplitude == d.amplitude[i]);
    CHECK(approximate[i].frequency == d.frequency[i]);
    CHECK(approximate[i].measures.stiffness == direct[i].measures.stiffness);
    CHECK(approximate[i].measures.phase == direct[i].measures.phase);
  }
  const runtime::ThesisCorrection correction{{1.1, 0.9, 1.02, 0.98}, {0.8, 1.25, 1.0, 1.05}};
  auto calibrated = direct;
  runtime::apply_correction(correction, calibrated);
  const auto corrected = runtime::predict(network, set, runtime::FitMethod::corrected, {}, &correction).points;
  REQUIRE(corrected.size() == calibrated.size());
  for (std::size_t i = 0; i < direct.size(); ++i) {
    CHECK(corrected[i].measures.stiffness == calibrated[i].measures.stiffness);
    CHECK(corrected[i].measures.phase == calibrated[i].measures.phase);
    CHECK(corrected[i].measures.stiffness == doctest::Approx(direct[i].measures.stiffness * correction.stiffness[i]).epsilon(1e-14));
  }
  CHECK_THROWS_AS(runtime::predict(network, set, runtime::FitMethod::corrected, {}, nullptr), std::logic_error);
  // The exact response is the harmonic module's periodic steady state, point by point.
  const auto exact = runtime::predict(network, set, runtime::FitMethod::exact, {}, nullptr).points;
  for (std::size_t i = 0; i < direct.size(); ++i) {
    const auto p = runtime::simulate_harmonic_point(network, d.amplitude[i], d.frequency[i], {});
    CHECK(exact[i].measures.stiffness == p.measures.stiffness);
    CHECK(exact[i].measures.phase == p.measures.phase);
  }
}

TEST_CASE("predict: for a linear network the approximation equals the exact response (independent paths)") {
  const auto network = test::network_from("model g { spring e (k = 100) maxwell m1 (k = 50, tau = 10 ms) maxwell m2 (k = 80, tau = 200 ms) }", "g");
  runtime::HarmonicData d;
  d.path = "g.csv";
  d.amplitude = {0.1, 0.5, 2.0};
  d.frequency = {0.3, 5.0, 45.0};
  d.stiffness = {1.0, 1.0, 1.0};
  d.phase = {0.1, 0.1, 0.1};
  d.rows = {3, 4, 5};
  const runtime::FitDataSet set{"g.csv", 1.0, d};
  const auto approximate = runtime::predict(network, set, runtime::FitMethod::approximate, {}, nullptr).points;
  const auto exact = runtime::predict(network, set, runtime::FitMethod::exact, {}, nullptr).points;
  for (std::size_t i = 0; i < exact.size(); ++i) {
    CHECK(test::relative_error(approximate[i].measures.stiffness, exact[i].measures.stiffness) < 1e-9);
    CHECK(std::abs(approximate[i].measures.phase - exact[i].measures.phase) < 1e-9);
  }
}

TEST_CASE("predict: a history is simulated whatever the method") {
  const auto network = test::network_from("model h { spring e (k = 100) friction f (k = 50, uy = 0.1) }", "h");
  const auto set = four_sample_history(1.0);
  const auto simulated = runtime::run_history(network, set.history().drive, false).force;
  for (const auto method : {runtime::FitMethod::exact, runtime::FitMethod::approximate, runtime::FitMethod::corrected}) {
    const auto p = runtime::predict(network, set, method, {}, nullptr);
    CHECK(p.points.empty());
    CHECK(p.force == simulated);
  }
  // Hand check of the simulation: spring 100 e plus the friction element (slips at 5 N):
  // e = 0.1 -> 10 + 5; e = -0.2 -> -20 - 5 (slipped back); e = 0.4 -> 40 + 5.
  check_equal(simulated, {0.0, 15.0, -25.0, 45.0}, 1e-12);
}

}  // namespace fit_scoring_test
