// harmonic_jacobian: where it applies; its residuals are those of the fit's scoring bit for bit;
// its Jacobian matches central differences of the scoring's residuals (an independent path:
// whole closed-form evaluations at moved coordinates) under both objectives and definitions,
// with weights and a damping term left out; a fit that uses it reaches the noise-free truth as
// the differenced one does, in fewer evaluations.
#include "runtime/fit/harmonic_jacobian.hpp"

#include "runtime/fit/fit.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace harmonic_jacobian_test {

using namespace rheo;

namespace {

const char* const kTruth = R"(model m {
  spring s (k = 120)
  yeoh y (D10 = 150, D20 = -2, D30 = 0.4)
  maxwell x (k = 80, tau = 4 ms)
  friction f1 (k = 300, uy = 30 um)
  friction f2 (k = 90, uy = 0.4 mm)
  slider sl (fy = 3 N)
  springpot sp (k = 30, alpha = 0.3, tau = 10 ms)
})";

// Every value moved from the truth's, within bounds (ln coordinates for the positive ones).
const char* const kStart = R"(model m {
  spring s (k = 100 in [1, 1000])
  yeoh y (D10 = 180 in [10, 1000], D20 = -1 in [-10, 10], D30 = 0.3 in [-2, 2])
  maxwell x (k = 60 in [1, 1000], tau = 6 ms in [0.1, 100])
  friction f1 (k = 250 in [1, 3000], uy = 25 um in [1, 1000])
  friction f2 (k = 110 in [1, 3000], uy = 0.3 mm in [0.001, 3])
  slider sl (fy = 4 N in [0.1, 100])
  springpot sp (k = 25 in [1, 300], alpha = 0.35 in [0.05, 0.9], tau = 10 ms)
})";

runtime::FitDataSet harmonic_of(const runtime::Network& truth, runtime::HarmonicDefinition definition, bool weighted) {
  runtime::HarmonicOptions options;
  options.definition = definition;
  runtime::HarmonicData data;
  data.path = "generated";
  for (double u0 : {0.01, 0.1, 0.6, 2.0})
    for (double f : {0.5, 5.0, 40.0}) {
      const auto p = runtime::simulate_harmonic_point(truth, u0, f, options);
      data.amplitude.push_back(u0), data.frequency.push_back(f);
      data.stiffness.push_back(p.measures.stiffness), data.phase.push_back(p.measures.phase);
      data.rows.push_back(static_cast<int>(data.rows.size()) + 2);
      if (weighted) data.weight.push_back(0.5 + 0.1 * static_cast<double>(data.rows.size()));
    }
  if (weighted) data.phase[1] = -0.001;  // a nearly elastic point's noise: its damping term is left out
  return {"generated", weighted ? 2.0 : 1.0, data};
}

std::vector<double> scored(const runtime::Network& network, const std::vector<runtime::FitDataSet>& data, const runtime::ScoreSettings& score) {
  std::vector<double> r;
  for (const runtime::FitDataSet& set : data)
    runtime::append_residuals(set, runtime::predict(network, set, runtime::FitMethod::exact, score.harmonic, nullptr), score, r);
  return r;
}

}  // namespace

TEST_CASE("the sensitivity Jacobian applies to closed-form harmonic fits of root-block networks only") {
  const runtime::Network root = test::network_from(kStart, "m");
  const runtime::Network nested = test::network_from(
      "model m { spring s (k = 5 in [1, 10]) series { spring a (k = 2) maxwell b (k = 3, tau = 1 ms) } }", "m");
  const std::vector<runtime::FitDataSet> data{harmonic_of(test::network_from(kTruth, "m"), runtime::HarmonicDefinition::thesis, false)};
  runtime::ScoreSettings score;
  CHECK(runtime::residual_jacobian_applies(root, data, score, runtime::FitMethod::exact));
  CHECK_FALSE(runtime::residual_jacobian_applies(nested, data, score, runtime::FitMethod::exact));
  CHECK_FALSE(runtime::residual_jacobian_applies(root, data, score, runtime::FitMethod::approximate));
  runtime::ScoreSettings stepped = score;
  stepped.harmonic.steady_state = runtime::SteadyState::time_stepping;
  CHECK_FALSE(runtime::residual_jacobian_applies(root, data, stepped, runtime::FitMethod::exact));
  std::vector<runtime::FitDataSet> preloaded = data;
  std::get<runtime::HarmonicData>(preloaded.front().data).preload.assign(data.front().harmonic().size(), 0.0);
  CHECK(runtime::residual_jacobian_applies(root, preloaded, score, runtime::FitMethod::exact));
  std::get<runtime::HarmonicData>(preloaded.front().data).preload[3] = 0.2;
  CHECK_FALSE(runtime::residual_jacobian_applies(root, preloaded, score, runtime::FitMethod::exact));
}

TEST_CASE("the sensitivity Jacobian matches central differences of the scored residuals") {
  const runtime::Network truth = test::network_from(kTruth, "m"), start = test::network_from(kStart, "m");
  const std::vector<int> free = runtime::bounded_parameters(start);
  const runtime::Coordinates coordinates(start, free);
  for (runtime::HarmonicDefinition definition : {runtime::HarmonicDefinition::thesis, runtime::HarmonicDefinition::first_harmonic})
    for (runtime::FitObjective objective : {runtime::FitObjective::phi, runtime::FitObjective::least_squares}) {
      runtime::ScoreSettings score;
      score.harmonic.definition = definition;
      score.objective = objective;
      score.stiffness_weight = 0.7, score.damping_weight = 0.3;
      const std::vector<runtime::FitDataSet> data{harmonic_of(truth, definition, false), harmonic_of(truth, definition, true)};
      const runtime::ResidualsWithJacobian at = runtime::residual_jacobian(coordinates, coordinates.z0, data, score);
      const std::vector<double> r = scored(coordinates.network(coordinates.z0), data, score);  // exp(ln p): p to rounding
      REQUIRE(at.residuals == r);
      REQUIRE(at.jacobian.rows() == static_cast<Eigen::Index>(r.size()));
      REQUIRE(at.jacobian.cols() == static_cast<Eigen::Index>(free.size()));
      for (std::size_t j = 0; j < free.size(); ++j) {
        std::vector<double> z = coordinates.z0;
        const double h = 1e-6 * std::max(1.0, std::abs(z[j]));
        z[j] += h;
        const std::vector<double> up = scored(coordinates.network(z), data, score);
        z[j] -= 2.0 * h;
        const std::vector<double> down = scored(coordinates.network(z), data, score);
        double column = 0.0, error = 0.0;
        for (std::size_t i = 0; i < r.size(); ++i) {
          const double difference = (up[i] - down[i]) / (2.0 * h);
          column = std::max(column, std::abs(difference));
          error = std::max(error, std::abs(at.jacobian(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)) - difference));
        }
        INFO("definition " << static_cast<int>(definition) << ", objective " << static_cast<int>(objective) << ", parameter "
                           << start.model().parameters[static_cast<std::size_t>(free[j])].path);
        CHECK(column > 0.0);
        CHECK(error <= 1e-6 * column);
      }
      // The left-out damping term (point 2 of the weighted file, after the 12 points of the first) has a zero row under phi.
      if (objective == runtime::FitObjective::phi) CHECK(at.jacobian.row(24 + 3).norm() == 0.0);
    }
}

TEST_CASE("the sensitivity Jacobian on two threads is the one thread's, bit for bit") {
  // Two files: the second's rows start after the first's, whichever thread writes them.
  const runtime::Network truth = test::network_from(kTruth, "m"), start = test::network_from(kStart, "m");
  const std::vector<int> free = runtime::bounded_parameters(start);
  const runtime::Coordinates coordinates(start, free);
  runtime::ScoreSettings score;
  const std::vector<runtime::FitDataSet> data{harmonic_of(truth, score.harmonic.definition, false),
                                              harmonic_of(truth, score.harmonic.definition, true)};
  const runtime::ResidualsWithJacobian one = runtime::residual_jacobian(coordinates, coordinates.z0, data, score);
  score.harmonic.threads = 2;
  const runtime::ResidualsWithJacobian two = runtime::residual_jacobian(coordinates, coordinates.z0, data, score);
  REQUIRE(one.jacobian.size() > 0);
  CHECK(two.residuals == one.residuals);
  CHECK(two.jacobian == one.jacobian);
}

TEST_CASE("a fit by sensitivities reaches the noise-free truth as the differenced fit does, in fewer evaluations") {
  const runtime::Network truth = test::network_from(kTruth, "m"), start = test::network_from(kStart, "m");
  runtime::FitSettings settings;
  settings.statistics = false;
  settings.separable = false;
  const std::vector<runtime::FitDataSet> data{harmonic_of(truth, settings.score.harmonic.definition, false)};
  const std::vector<int> free = runtime::bounded_parameters(start);
  const runtime::FitResult by_sensitivities = runtime::fit(start, free, data, settings);
  settings.sensitivities = false;
  const runtime::FitResult differenced = runtime::fit(start, free, data, settings);
  CHECK(by_sensitivities.objective <= std::max(1e-14, 2.0 * differenced.objective));
  CHECK(by_sensitivities.evaluations < differenced.evaluations);
}

}  // namespace harmonic_jacobian_test
