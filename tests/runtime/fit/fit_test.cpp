// Identification (issue #3 acceptance): from a start off by a factor of 3 on every parameter,
// known models are recovered from their own noise-free data within 1e-3 relative; on the
// specimen C and D measurements the default strategy from a generic start reaches an err (6.1)
// no worse than the dissertation's Appendix D parameters give.
#include "runtime/fit/fit.hpp"
#include "runtime/protocols/run_history.hpp"
#include "runtime/protocols/harmonic.hpp"

#include "runtime/fit/objective.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <fstream>
#include <numbers>
#include <sstream>

namespace fit_test {

using namespace rheo;

namespace {

runtime::FitDataSet harmonic_set_from(const runtime::Network& truth, const std::vector<double>& amplitudes, const std::vector<double>& frequencies) {
  runtime::HarmonicData data;
  data.path = "generated";
  for (double u0 : amplitudes)
    for (double f : frequencies) {
      const auto p = runtime::simulate_harmonic_point(truth, u0, f, {});
      data.amplitude.push_back(u0), data.frequency.push_back(f);
      data.stiffness.push_back(p.measures.stiffness), data.phase.push_back(p.measures.phase);
      data.rows.push_back(0);
    }
  return {"generated", 1.0, data};
}

// Elements of a kind are interchangeable: order the pair (a, b) by `key` ("uy", "tau") as in
// the truth (a's key below b's), swapping every parameter named in `names`.
runtime::Network ordered(const runtime::Network& n, const std::string& a, const std::string& b, const std::string& key,
                         const std::vector<std::string>& names) {
  if (n.parameter(test::parameter_index(n, a + "." + key)) <= n.parameter(test::parameter_index(n, b + "." + key))) return n;
  std::vector<double> swapped = n.parameters();
  for (const auto& name : names)
    std::swap(swapped[static_cast<std::size_t>(test::parameter_index(n, a + "." + name))],
              swapped[static_cast<std::size_t>(test::parameter_index(n, b + "." + name))]);
  return n.with_parameters(swapped);
}

runtime::FitResult in_truth_order(runtime::FitResult result, const char* kind) {
  result.network = std::string(kind) == "friction" ? ordered(result.network, "f1", "f2", "uy", {"k", "uy", "fy"})
                                                   : ordered(result.network, "m1", "m2", "tau", {"k", "tau", "c"});
  return result;
}

void check_recovered(const runtime::FitResult& result, const runtime::Network& truth) {
  for (int i : result.free) {
    CAPTURE(result.network.model().parameters[static_cast<std::size_t>(i)].path);
    CAPTURE(result.network.parameter(i));
    CAPTURE(truth.parameter(i));
    CHECK(test::relative_error(result.network.parameter(i), truth.parameter(i)) < 1e-3);
  }
}


}  // namespace

TEST_CASE("linear viscoelastic: a two-Maxwell solid is recovered from 3x off") {
  const auto truth = test::network_from("model g { spring e (k = 100) maxwell m1 (k = 50, tau = 10 ms) maxwell m2 (k = 80, tau = 200 ms) }", "g");
  const auto start = test::network_from(R"(model g {
      spring e (k = 300 in [1, 10000])
      maxwell m1 (k = 150 in [1, 10000], tau = 30 ms in [0.01, 100000])
      maxwell m2 (k = 26.6667 in [1, 10000], tau = 66.6667 ms in [0.01, 100000]) })",
                                        "g");
  const auto data = harmonic_set_from(truth, {0.5}, {0.1, 0.3, 1.0, 3.0, 10.0, 30.0, 50.0});
  const auto result = runtime::fit(start, runtime::bounded_parameters(start), {data}, {});
  check_recovered(in_truth_order(result, "maxwell"), truth);
  CHECK(result.err < 1e-6);
  CHECK_FALSE(result.interrupted);
}

TEST_CASE("with friction elements: spring + Maxwell + 2 friction recovered from 3x off") {
  const auto truth = test::network_from(
      "model f { spring e (k = 400) maxwell m (k = 60, tau = 5 ms) friction f1 (k = 300, uy = 40 um) friction f2 (k = 80, uy = 150 um) }", "f");
  const auto start = test::network_from(R"(model f {
      spring e (k = 1200 in [1, 10000])
      maxwell m (k = 20 in [1, 10000], tau = 15 ms in [0.01, 100000])
      friction f1 (k = 100 in [1, 10000], uy = 120 um in [0.1, 10000])
      friction f2 (k = 240 in [1, 10000], uy = 50 um in [0.1, 10000]) })",
                                        "f");
  const auto data = harmonic_set_from(truth, {0.01, 0.03, 0.06, 0.1, 0.2, 0.5, 1.0}, {1.0, 10.0, 30.0, 50.0});
  const auto result = runtime::fit(start, runtime::bounded_parameters(start), {data}, {});
  CHECK(result.err < 1e-6);
  check_recovered(in_truth_order(result, "friction"), truth);
}

TEST_CASE("an extra start is searched from too: with a budget too small to get there from the start, the fit finds the truth near it") {
  const auto truth = test::network_from("model g { spring e (k = 100) maxwell m1 (k = 50, tau = 10 ms) }", "g");
  const auto start = test::network_from(
      "model g { spring e (k = 300 in [1, 10000])\n maxwell m1 (k = 5 in [1, 10000], tau = 1 s in [0.01, 100000]) }", "g");
  const auto data = harmonic_set_from(truth, {0.5}, {0.1, 1.0, 10.0, 50.0});
  runtime::FitSettings settings;
  settings.separable = false;  // the search itself, not the solve of the scales
  settings.search.max_evaluations = 30;
  settings.search.samples = 0;
  const auto alone = runtime::fit(start, runtime::bounded_parameters(start), {data}, settings);
  std::vector<double> near = truth.parameters();
  for (double& v : near) v *= 1.05;  // 5 % off: not a point the search evaluates by chance
  settings.extra_starts = {near};
  const auto helped = runtime::fit(start, runtime::bounded_parameters(start), {data}, settings);
  CAPTURE(alone.err);
  CHECK(helped.err < 1e-9);
  CHECK(alone.err > 1e-3);
  // A start outside the bounds is clamped into them; one of the wrong length is a caller's bug.
  near[static_cast<std::size_t>(test::parameter_index(start, "e.k"))] = 1e9;
  settings.extra_starts = {near};
  CHECK_NOTHROW(runtime::fit(start, runtime::bounded_parameters(start), {data}, settings));
  settings.extra_starts = {{1.0, 2.0}};
  CHECK_THROWS_AS(runtime::fit(start, runtime::bounded_parameters(start), {data}, settings), std::logic_error);
}

// The fit starts the yeoh constants from the mean curve of the loop (eqs. 5.28-5.32) by
// default, then searches all parameters against the time-domain residual.
TEST_CASE("yeoh spring from a static loop (time-domain residual), from 3x off") {
  const auto truth = test::network_from(
      "model y { yeoh r (D10 = 389.4253, D20 = -2.1094, D30 = 0.0786) friction f1 (k = 300, uy = 40 um) friction f2 (k = 80, uy = 150 um) }", "y");
  const auto start = test::network_from(R"(model y {
      yeoh r (D10 = 129.8 in [1, 10000], D20 = -6.3282 in [-100, 100], D30 = 0.0262 in [-10, 10])
      friction f1 (k = 900 in [1, 10000], uy = 13.3333 um in [0.1, 10000])
      friction f2 (k = 26.6667 in [1, 10000], uy = 450 um in [0.1, 10000]) })",
                                        "y");
  const auto data = test::history_data_of(truth, runtime::static_triangle({6.25, 3.0, 1.2, 0.6, 0.3, 0.12}, 0.05, 2, 400));
  const auto result = runtime::fit(start, runtime::bounded_parameters(start), {data}, {});
  CHECK(result.datasets.at(0).err < 1e-7);
  check_recovered(in_truth_order(result, "friction"), truth);
}

// A rig history that begins at a preload (#25 item 1): the measured force at the first sample is
// the elastic springs' alone, and the fit recovers every parameter from it.
TEST_CASE("a history from a preloaded start: the relaxed start is fitted, every parameter back from 3x off") {
  const auto truth = test::network_from(
      "model p { yeoh r (D10 = 200, D20 = 1.5, D30 = 0.05) maxwell m (k = 120, tau = 30 ms) friction f (k = 400, uy = 60 um) }", "p");
  const auto start = test::network_from(R"(model p {
      yeoh r (D10 = 66.7 in [1, 10000], D20 = 4.5 in [-100, 100], D30 = 0.15 in [-10, 10])
      maxwell m (k = 360 in [1, 10000], tau = 10 ms in [0.1, 10000])
      friction f (k = 133.3 in [1, 10000], uy = 180 um in [0.1, 10000]) })",
                                        "p");
  runtime::Drive drive;  // held at 2 mm, then a 2 Hz sine of 0.8 mm about it
  for (int k = 0; k <= 800; ++k) {
    drive.time.push_back(k * 1.25e-3);
    drive.displacement.push_back(2.0 + 0.8 * std::sin(2.0 * std::numbers::pi * 2.0 * k * 1.25e-3));
  }
  const auto data = test::history_data_of(truth, drive);
  CHECK(data.history().force.front() == doctest::Approx(test::yeoh_force(200, 1.5, 0.05, 2.0)).epsilon(1e-14));
  const auto result = runtime::fit(start, runtime::bounded_parameters(start), {data}, {});
  CHECK(result.datasets.at(0).err < 1e-7);
  check_recovered(result, truth);
}

// A rig that tests about several preloads (#25 item 3): only the preloads tell D20 and D30 apart
// from the amplitude dependence; each point is simulated about its own p.
TEST_CASE("harmonic data at several preloads: the yeoh constants come back from the preload dependence") {
  const auto truth = test::network_from("model y { yeoh r (D10 = 300, D20 = -1.2, D30 = 0.06) maxwell m (k = 80, tau = 8 ms) }", "y");
  const auto start = test::network_from(R"(model y {
      yeoh r (D10 = 100 in [1, 10000], D20 = 1 in [-100, 100], D30 = 0.5 in [-10, 10])
      maxwell m (k = 240 in [1, 10000], tau = 3 ms in [0.1, 10000]) })",
                                        "y");
  runtime::HarmonicData data;
  data.path = "preloads";
  for (double preload : {-3.0, 0.0, 1.5, 3.0})
    for (double f : {1.0, 10.0, 40.0}) {
      const auto p = runtime::simulate_harmonic_point(truth, 0.2, f, {}, preload);
      data.amplitude.push_back(0.2), data.frequency.push_back(f), data.preload.push_back(preload);
      data.stiffness.push_back(p.measures.stiffness), data.phase.push_back(p.measures.phase);
      data.weight.push_back(1.0), data.rows.push_back(0);
    }
  const auto result = runtime::fit(start, runtime::bounded_parameters(start), {{"preloads", 1.0, data}}, {});
  CHECK(result.datasets.at(0).err < 1e-8);
  check_recovered(result, truth);
}

TEST_CASE("specimens C and D: the default strategy from a generic start matches or beats Appendix D") {
  for (const char* specimen : {"c", "d"}) {
    CAPTURE(specimen);
    const std::string dir = RHEO_EXAMPLES_DIR;
    const auto appendix = test::network_from(test::read_file(fmt::format("{}/specimen_{}.rheo", dir, specimen)),
                                             fmt::format("specimen_{}", specimen));
    const auto start = test::network_from(test::read_file(fmt::format("{}/specimen_{}_fit.rheo", dir, specimen)),
                                          fmt::format("specimen_{}", specimen));
    const auto data = runtime::read_fit_data(fmt::format("{}/data/specimen_{}_harmonic.csv", dir, static_cast<char>(std::toupper(specimen[0]))), 1.0);
    const auto appendix_points = runtime::predict(appendix, data, runtime::FitMethod::exact, {}, nullptr).points;
    const double appendix_err = runtime::thesis_err(runtime::relative_residuals(data.harmonic(), appendix_points));
    const auto result = runtime::fit(start, runtime::bounded_parameters(start), {data}, {});
    CAPTURE(appendix_err);
    CAPTURE(result.err);
    CHECK(result.err <= appendix_err);
  }
}

TEST_CASE("a model without free parameters cannot be fitted, and says how to declare one") {
  const auto net = test::network_from("model z { spring e (k = 100) }", "z");
  CHECK_THROWS_WITH_AS(runtime::fit(net, {}, {}, {}), doctest::Contains("give bounds"), std::logic_error);
}

// err (6.1) as the fit reports it, over all harmonic files and per file, on residuals worked out
// by hand: a spring bounded to [200, 300] N/mm against stiffnesses of 100-200 N/mm ends on its
// lower bound (phi falls towards k = sum(1/K) / sum(1/K^2) = 135.5 N/mm), and its phase is 0.
TEST_CASE("the fit's err (6.1): sqrt of the summed phi over the total number of points, per file and over both") {
  const double deg = std::numbers::pi / 180.0;
  auto table = [](const std::string& path, const std::vector<double>& stiffness, const std::vector<double>& phase) {
    runtime::HarmonicData d;
    d.path = path;
    for (std::size_t i = 0; i < stiffness.size(); ++i) {
      d.amplitude.push_back(0.5), d.frequency.push_back(static_cast<double>(i + 1));
      d.stiffness.push_back(stiffness[i]), d.phase.push_back(phase[i]), d.rows.push_back(static_cast<int>(i) + 2);
    }
    return runtime::FitDataSet{path, 1.0, d};
  };
  // At k = 200: stiffness residuals 1, 0.6, 0.25, 0 and 0.25; damping sin(0)/sin(phase) - 1 = -1
  // where the measured phase is positive, left out where it is 0.
  const auto first = table("first.csv", {100.0, 125.0, 160.0, 200.0}, {10.0 * deg, 20.0 * deg, 0.0, 0.0});
  const auto second = table("second.csv", {160.0}, {0.0});
  const auto start = test::network_from("model s { spring e (k = 250 N/mm in [200, 300]) }", "s");
  const auto result = runtime::fit(start, runtime::bounded_parameters(start), {first, second}, {});
  REQUIRE(result.datasets.size() == 2);
  CHECK(result.network.parameter(0) == doctest::Approx(200.0).epsilon(1e-9));
  // first.csv: phi = 1 + 0.36 + 0.0625 + 0 + 1 + 1 = 3.4225, err = sqrt(3.4225) / 4 = 1.85 / 4 = 0.4625.
  CHECK(result.datasets[0].phi == doctest::Approx(3.4225).epsilon(1e-8));
  CHECK(result.datasets[0].err == doctest::Approx(0.4625).epsilon(1e-8).scale(0.0));
  // second.csv: phi = 0.0625, err = 0.25 / 1.
  CHECK(result.datasets[1].err == doctest::Approx(0.25).epsilon(1e-8).scale(0.0));
  // Both: phi = 3.485 over n = 5 points, err = sqrt(3.485) / 5 = 0.373363; not the mean of the
  // files' errs (0.35625), nor over n - 1 (0.466704), nor the root of phi / n (0.834865).
  CHECK(result.phi == doctest::Approx(3.485).epsilon(1e-8));
  CHECK(result.err == doctest::Approx(0.3733630940518894).epsilon(1e-8).scale(0.0));
}

}  // namespace fit_test
