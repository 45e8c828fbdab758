// separable_fit: the force scales solved for a given shape recover the generating values from
// noise-free data (harmonic under both objectives and definitions, histories), respect their
// bounds, and a whole fit that uses them reaches the objective of the plain search.
#include "runtime/fit/separable_fit.hpp"

#include "runtime/fit/fit.hpp"
#include "runtime/fit/force_scales.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/protocols/run_history.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace separable_fit_test {

using namespace rheo;

namespace {

runtime::FitDataSet harmonic_of(const runtime::Network& truth, runtime::HarmonicDefinition definition) {
  runtime::HarmonicOptions options;
  options.definition = definition;
  runtime::HarmonicData data;
  data.path = "generated";
  for (double u0 : {0.05, 0.3, 1.0})
    for (double f : {0.5, 3.0, 12.0, 40.0}) {
      const auto p = runtime::simulate_harmonic_point(truth, u0, f, options);
      data.amplitude.push_back(u0), data.frequency.push_back(f);
      data.stiffness.push_back(p.measures.stiffness), data.phase.push_back(p.measures.phase);
      data.rows.push_back(0);
    }
  return {"generated", 1.0, data};
}

struct Scales {
  std::vector<int> index;
  std::vector<double> lower, upper;
};

Scales scales_of(const runtime::Network& network) {
  Scales s;
  const std::vector<int> free = runtime::bounded_parameters(network);
  for (int j : runtime::force_scales(network, free)) {
    const auto& p = network.model().parameters[static_cast<std::size_t>(free[static_cast<std::size_t>(j)])];
    s.index.push_back(free[static_cast<std::size_t>(j)]);
    s.lower.push_back(p.lower), s.upper.push_back(p.upper);
  }
  return s;
}

const char* const coupled_truth = "model m { spring s (k = 120) maxwell x (k = 60, tau = 5 ms) friction f (k = 80, uy = 0.1 mm) }";
const char* const coupled_start =
    "model m { spring s (k = 5 in [1, 1000]) maxwell x (k = 900 in [1, 1000], tau = 5 ms) friction f (k = 2 in [1, 1000], uy = 0.1 mm) }";

}  // namespace

TEST_CASE("predictions are affine in the scales for histories, the first harmonic, and linear networks") {
  const auto linear = test::network_from("model m { spring s (k = 1 in [0.1, 10]) maxwell x (k = 1 in [0.1, 10], tau = 1 ms) }", "m");
  const auto friction = test::network_from(coupled_truth, "m");
  runtime::ScoreSettings thesis, first;
  first.harmonic.definition = runtime::HarmonicDefinition::first_harmonic;
  const std::vector<runtime::FitDataSet> harmonic{harmonic_of(friction, runtime::HarmonicDefinition::thesis)},
      history{test::history_data_of(friction, runtime::quasistatic_sine({1.0, 0.3}, 2.0, 2, 400))};
  CHECK(runtime::predictions_affine(linear, harmonic, thesis));
  CHECK_FALSE(runtime::predictions_affine(friction, harmonic, thesis));  // F^ is a maximum over the cycle
  CHECK(runtime::predictions_affine(friction, harmonic, first));
  CHECK(runtime::predictions_affine(friction, history, thesis));
  runtime::ScoreSettings approximate = first;
  approximate.method = runtime::FitMethod::approximate;
  CHECK_FALSE(runtime::predictions_affine(friction, harmonic, approximate));
}

TEST_CASE("the scales of a friction model come back from its first-harmonic grid and from its history, far from the start") {
  const auto truth = test::network_from(coupled_truth, "m");
  const auto start = test::network_from(coupled_start, "m");
  const Scales s = scales_of(start);
  REQUIRE(s.index.size() == 3);
  for (const runtime::FitObjective objective : {runtime::FitObjective::phi, runtime::FitObjective::least_squares}) {
    runtime::ScoreSettings score;
    score.objective = objective;
    score.harmonic.definition = runtime::HarmonicDefinition::first_harmonic;
    for (const runtime::FitDataSet& set :
         {harmonic_of(truth, score.harmonic.definition), test::history_data_of(truth, runtime::quasistatic_sine({1.0, 0.3}, 2.0, 2, 400))}) {
      const auto solved = runtime::solve_scales(start, s.index, s.lower, s.upper, {set}, score);
      CAPTURE(set.is_harmonic());
      CHECK(solved.evaluations == 4);
      CHECK(solved.values[static_cast<std::size_t>(test::parameter_index(start, "s.k"))] == doctest::Approx(120.0).epsilon(1e-8));
      CHECK(solved.values[static_cast<std::size_t>(test::parameter_index(start, "x.k"))] == doctest::Approx(60.0).epsilon(1e-8));
      CHECK(solved.values[static_cast<std::size_t>(test::parameter_index(start, "f.k"))] == doctest::Approx(80.0).epsilon(1e-8));
      CHECK(solved.objective < 1e-18);
    }
  }
}

TEST_CASE("a scale the data would push beyond its bound stops on it, where no feasible move lowers the objective") {
  const auto truth = test::network_from(coupled_truth, "m");
  const auto start = test::network_from(
      "model m { spring s (k = 5 in [1, 1000]) maxwell x (k = 20 in [1, 40], tau = 5 ms) friction f (k = 2 in [1, 1000], uy = 0.1 mm) }", "m");
  const std::vector<runtime::FitDataSet> data{harmonic_of(truth, runtime::HarmonicDefinition::thesis)};
  runtime::ScoreSettings score;
  score.harmonic.definition = runtime::HarmonicDefinition::first_harmonic;
  const Scales s = scales_of(start);
  const auto solved = runtime::solve_scales(start, s.index, s.lower, s.upper, data, score);
  CHECK(solved.values[static_cast<std::size_t>(test::parameter_index(start, "x.k"))] == 40.0);
  // The objective of the model itself (not the affine response) at the solution and around it.
  auto objective_at = [&](std::vector<double> values) {
    std::vector<double> r;
    const auto network = start.with_parameters(values);
    runtime::append_residuals(data[0], runtime::predict(network, data[0], runtime::FitMethod::exact, score.harmonic, nullptr), score, r);
    double sum = 0.0;
    for (double v : r) sum += v * v;
    return sum;
  };
  CHECK(objective_at(solved.values) == doctest::Approx(solved.objective).epsilon(1e-9).scale(0.0));
  for (const int parameter : s.index)
    for (double factor : {0.999, 1.001}) {
      std::vector<double> moved = solved.values;
      const auto at = static_cast<std::size_t>(parameter);
      moved[at] = std::min(moved[at] * factor, start.model().parameters[at].upper);
      CAPTURE(parameter);
      CAPTURE(factor);
      CHECK(objective_at(moved) >= solved.objective * (1.0 - 1e-12));
    }
}

TEST_CASE("a fit with free shapes solves its scales inside the search and finds the truth, as the plain search does") {
  const auto truth = test::network_from(coupled_truth, "m");
  const auto start = test::network_from(
      "model m { spring s (k = 30 in [1, 1000]) maxwell x (k = 20 in [1, 1000], tau = 1 ms in [0.1 ms, 100 ms]) "
      "friction f (k = 30 in [1, 1000], uy = 0.3 mm in [0.01 mm, 3 mm]) }",
      "m");
  runtime::FitSettings settings;
  settings.score.harmonic.definition = runtime::HarmonicDefinition::first_harmonic;
  const std::vector<runtime::FitDataSet> data{harmonic_of(truth, settings.score.harmonic.definition)};
  const auto separable = runtime::fit(start, runtime::bounded_parameters(start), data, settings);
  settings.separable = false;
  const auto plain = runtime::fit(start, runtime::bounded_parameters(start), data, settings);
  for (const auto* result : {&separable, &plain}) {
    CHECK(result->network.parameter(test::parameter_index(start, "s.k")) == doctest::Approx(120.0).epsilon(1e-5));
    CHECK(result->network.parameter(test::parameter_index(start, "x.k")) == doctest::Approx(60.0).epsilon(1e-5));
    CHECK(result->network.parameter(test::parameter_index(start, "x.tau")) == doctest::Approx(5e-3).epsilon(1e-5).scale(0.0));
    CHECK(result->network.parameter(test::parameter_index(start, "f.uy")) == doctest::Approx(0.1).epsilon(1e-5).scale(0.0));
    CHECK(result->err < 1e-7);
  }
  REQUIRE_FALSE(separable.notes.empty());
  CHECK(separable.notes.front().find("3 of the 5 free parameters solved exactly") == 0);
  MESSAGE("evaluations: separable " << separable.evaluations << ", plain " << plain.evaluations);
}

}  // namespace separable_fit_test
