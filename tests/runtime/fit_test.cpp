// Identification from a start off by a factor of 3 on every parameter recovers a known model
// from its own noise-free harmonic response (issue #3 acceptance, linear viscoelastic case).
#include "runtime/fit.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

using namespace rheo;

TEST_CASE("fit recovers a Zener model from its own data, from 3x off, in log space") {
  const auto truth = test::network_from("model z { spring e (k = 100) maxwell m (k = 50, tau = 10 ms) }", "z");
  runtime::HarmonicData data;
  for (double f : {1.0, 5.0, 10.0, 20.0, 40.0}) {
    const auto p = runtime::simulate_harmonic_point(truth, 0.5, f, {});
    data.amplitude.push_back(0.5), data.frequency.push_back(f);
    data.stiffness.push_back(p.measures.stiffness), data.phase.push_back(p.measures.phase);
    data.rows.push_back(0);
  }
  const auto start = test::network_from(
      "model z { spring e (k = 300 in [1, 10000]) maxwell m (k = 150 in [1, 10000], tau = 30 ms in [0.1, 1000]) }", "z");
  runtime::FitSettings settings;
  const auto result = runtime::fit_harmonic(start, data, settings);
  const auto& params = result.network.model().parameters;
  for (int i : result.free) {
    const double truth_value = truth.parameter(i);
    CAPTURE(params[static_cast<std::size_t>(i)].path);
    CHECK(test::relative_error(result.network.parameter(i), truth_value) < 1e-3);
  }
  CHECK(result.err < 1e-6);
}

TEST_CASE("a model without free parameters cannot be fitted, and says how to declare one") {
  const auto net = test::network_from("model z { spring e (k = 100) }", "z");
  runtime::HarmonicData data;
  CHECK_THROWS_WITH_AS(runtime::fit_harmonic(net, data, {}), doctest::Contains("give bounds"), std::invalid_argument);
}
