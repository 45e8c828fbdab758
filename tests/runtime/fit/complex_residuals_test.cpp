// ComplexResiduals (runtime/fit/complex_residuals.hpp) against the independent path it stands
// in for: append_residuals on points of stiffness |K*| and phase arg K*, for both objectives,
// with file and point weights, term weights, model points on either side of a resonance
// (K' < 0), measured phases whose damping term is left out (<= 0, >= 180 deg) and shifts.
#include "runtime/fit/complex_residuals.hpp"

#include "portable_random.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <complex>
#include <numbers>
#include <stdexcept>

namespace complex_residuals_test {

using namespace rheo;

namespace {

constexpr double deg = std::numbers::pi / 180.0;

runtime::FitDataSet table(std::size_t n, unsigned seed, bool point_weights) {
  test::PortableRandom random(seed);
  runtime::HarmonicData d;
  d.path = "grid.csv";
  for (std::size_t i = 0; i < n; ++i) {
    d.amplitude.push_back(0.1 * static_cast<double>(i + 1));
    d.frequency.push_back(static_cast<double>(i + 1));
    d.stiffness.push_back(100.0 * std::exp(random.normal()));
    d.phase.push_back((60.0 + 70.0 * random.normal()) * deg);  // some beyond 90 deg, some <= 0 or >= 180 deg
    d.rows.push_back(static_cast<int>(i) + 2);
    if (point_weights) d.weight.push_back(0.5 + std::abs(random.normal()));
  }
  d.phase[0] = 0.0, d.phase[1] = 180.0 * deg, d.phase[2] = -3.0 * deg;  // damping terms left out
  return {"grid.csv", 2.5, d};
}

}  // namespace

TEST_CASE("complex residuals: the terms append_residuals gives for stiffness |K*| and phase arg K*") {
  for (const auto objective : {runtime::FitObjective::phi, runtime::FitObjective::least_squares})
    for (const bool point_weights : {false, true}) {
      const runtime::FitDataSet set = table(40, point_weights ? 7u : 5u, point_weights);
      runtime::ScoreSettings score;
      score.objective = objective;
      score.stiffness_weight = 0.7, score.damping_weight = 0.3;
      test::PortableRandom random(11);
      std::vector<std::complex<double>> model;
      for (std::size_t j = 0; j < 40; ++j) model.push_back(std::polar(100.0 * std::exp(random.normal()), (60.0 + 80.0 * random.normal()) * deg));
      const runtime::ComplexResiduals residuals(set, score);
      for (const double shift : {0.0, 35.0, -250.0}) {
        runtime::Prediction prediction;
        for (const auto& k : model) {
          runtime::HarmonicPoint point;
          point.measures.stiffness = std::abs(k + shift);
          point.measures.phase = std::arg(k + shift);
          prediction.points.push_back(point);
        }
        std::vector<double> expected, terms;
        runtime::append_residuals(set, prediction, score, expected);
        const double sum = residuals.terms(model, shift, terms);
        REQUIRE(terms.size() == expected.size());
        double expected_sum = 0.0;
        int negative_storage = 0;
        for (std::size_t i = 0; i < terms.size(); ++i) {
          const double want = expected[i], got = terms[i];
          CAPTURE(i);
          CAPTURE(shift);
          CHECK(std::abs(got - want) <= 1e-12 * (1.0 + std::abs(want)));
          expected_sum += want * want;
        }
        for (const auto& k : model) negative_storage += (k + shift).real() < 0.0;
        CHECK(std::abs(sum - expected_sum) <= 1e-12 * expected_sum);
        if (objective == runtime::FitObjective::phi) {
          // The left-out damping terms are exactly 0, the others are not.
          CHECK(terms[1] == 0.0);
          CHECK(terms[3] == 0.0);
          CHECK(terms[5] == 0.0);
          CHECK(terms[7] != 0.0);
        }
        if (shift == -250.0) CHECK(negative_storage > 0);  // points beyond a resonance are among them
      }
    }
}

TEST_CASE("complex residuals: a history, or a model of another size, is refused") {
  runtime::HistoryData h;
  h.drive = {{0.0, 1.0}, {0.0, 0.1}};
  h.force = {0.0, 1.0};
  h.rows = {2, 3};
  h.force_scale = 1.0;
  const runtime::ScoreSettings score;
  CHECK_THROWS_AS(runtime::ComplexResiduals(runtime::FitDataSet{"h.csv", 1.0, h}, score), std::logic_error);
  const runtime::ComplexResiduals residuals(table(5, 3, false), score);
  std::vector<double> out;
  CHECK_THROWS_AS(residuals.terms(std::vector<std::complex<double>>(4, {100.0, 10.0}), 0.0, out), std::logic_error);
}

}  // namespace complex_residuals_test
