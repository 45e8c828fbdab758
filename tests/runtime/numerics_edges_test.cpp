// Numerics at the edges (issue #8): relaxation times far below the step, slip displacements
// tending to zero, a zero-amplitude point, stiffness ratios of 1e9 in one network, parameters
// on their bounds (at the start and at the optimum), and fits that repeat bit for bit.
// (Non-finite objectives: optimizer_test and fit_search_test.) Each against a closed form or a
// second path, with tolerances that fail on a wrong answer.
#include "runtime/fit/fit.hpp"
#include "runtime/protocols/harmonic.hpp"
#include "runtime/closed_form/periodic_closed_form.hpp"
#include "runtime/closed_form/phasor.hpp"
#include "support.hpp"

#include <doctest/doctest.h>
#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>

namespace numerics_edges_test {

using namespace rheo;

namespace {

runtime::HarmonicPoint stepped(const runtime::Network& net, double u0, double f, runtime::SolverChoice solver) {
  runtime::HarmonicOptions o;
  o.steady_state = runtime::SteadyState::time_stepping;
  o.solver = solver;
  return runtime::simulate_harmonic_point(net, u0, f, o);
}

void check_close(const runtime::HarmonicPoint& p, std::complex<double> k_star, double stiffness_tolerance, double phase_tolerance) {
  CHECK(p.converged);
  CHECK(std::isfinite(p.measures.stiffness));
  CHECK(test::relative_error(p.measures.stiffness, std::abs(k_star)) < stiffness_tolerance);
  CHECK(std::abs(p.measures.phase - std::arg(k_star)) < phase_tolerance);
}

runtime::FitDataSet harmonic_data_of(const runtime::Network& truth, const std::vector<double>& amplitudes, const std::vector<double>& frequencies,
                                     const runtime::HarmonicOptions& options) {
  runtime::HarmonicData data;
  data.path = "generated";
  for (double u0 : amplitudes)
    for (double f : frequencies) {
      const auto p = runtime::simulate_harmonic_point(truth, u0, f, options);
      data.amplitude.push_back(u0), data.frequency.push_back(f);
      data.stiffness.push_back(p.measures.stiffness), data.phase.push_back(p.measures.phase);
      data.rows.push_back(0);
    }
  return {"generated", 1.0, data};
}

}  // namespace

TEST_CASE("a Maxwell element relaxing 1e6 times faster than the step is its tiny dashpot, on every path") {
  // tau = 1e-10 s against dt = 1/(2048 * 5 Hz) ~ 1e-4 s.
  const auto net = test::network_from("model m { spring e (k = 100) maxwell fast (k = 1e4, tau = 1e-10 s) }", "m");
  const double f = 5.0, w = 2 * std::numbers::pi * f;
  const std::complex<double> exact = 100.0 + std::complex<double>{0.0, w * 1e4 * 1e-10};
  check_close(runtime::closed_form_harmonic_point(net, 1.0, f, runtime::HarmonicDefinition::thesis), exact, 1e-12, 1e-12);
  check_close(stepped(net, 1.0, f, runtime::SolverChoice::fixed), exact, 1e-6, 1e-8);
  // Nested behind a spring, the tree solver and IDA see the same stiff element.
  const auto nested = test::network_from("model n { series { spring e (k = 100) maxwell fast (k = 1e4, tau = 1e-10 s) } }", "n");
  const auto k_star = runtime::complex_stiffness(nested.model(), nested.parameters(), f);
  REQUIRE(k_star);
  // Fixed steps are first order in a dashpot behind an internal node (docs/numerics.md).
  check_close(stepped(nested, 1.0, f, runtime::SolverChoice::fixed), *k_star, 1e-5, 1e-4);
  check_close(stepped(nested, 1.0, f, runtime::SolverChoice::sundials), *k_star, 1e-5, 1e-5);
}

TEST_CASE("a friction element whose slip displacement tends to zero becomes a slider") {
  const auto slider = test::network_from("model s { spring e (k = 50) slider s (fy = 2 N) }", "s");
  for (double uy : {1e-6, 1e-9, 1e-12}) {
    const auto friction = test::network_from(fmt::format("model f {{ spring e (k = 50) friction s (k = {}, fy = 2 N) }}", 2.0 / uy), "f");
    for (double u0 : {1e-3, 0.5}) {
      const auto a = runtime::closed_form_harmonic_point(friction, u0, 3.0, runtime::HarmonicDefinition::thesis);
      const auto b = runtime::closed_form_harmonic_point(slider, u0, 3.0, runtime::HarmonicDefinition::thesis);
      const auto c = stepped(friction, u0, 3.0, runtime::SolverChoice::fixed);
      CAPTURE(uy);
      CAPTURE(u0);
      CHECK(test::relative_error(a.measures.stiffness, b.measures.stiffness) < 10 * uy / u0);
      CHECK(std::abs(a.measures.phase - b.measures.phase) < 10 * uy / u0);
      CHECK(c.converged);
      CHECK(test::relative_error(c.measures.stiffness, b.measures.stiffness) < 1e-5 + 10 * uy / u0);
    }
  }
}

// IDA holds internal node positions as unknowns: behind a 1e9 N/mm spring, a position error
// within IDA's default Newton tolerance was a 1e-2 force error (dae_newton_tolerance).
TEST_CASE("stiffness ratios of 1e9 in one network: a soft arm behind a stiff one, a stiff one beside a soft one") {
  const auto net = test::network_from(R"(
    model r {
      spring soft (k = 1)
      series { spring stiff (k = 1e9) maxwell m (k = 1, tau = 10 ms) }
      series { spring stiff2 (k = 1e9) parallel { spring s (k = 2) dashpot d (c = 0.01 N*s/mm) } }
    })",
                                      "r");
  for (double f : {0.5, 16.0}) {
    const auto k_star = runtime::complex_stiffness(net.model(), net.parameters(), f);
    REQUIRE(k_star);
    CAPTURE(f);
    check_close(runtime::closed_form_harmonic_point(net, 0.2, f, runtime::HarmonicDefinition::thesis), *k_star, 1e-9, 1e-9);
    check_close(stepped(net, 0.2, f, runtime::SolverChoice::fixed), *k_star, 1e-3, 2e-3);  // first order, as above
    check_close(stepped(net, 0.2, f, runtime::SolverChoice::sundials), *k_star, 1e-5, 1e-5);
  }
}

TEST_CASE("a zero-amplitude point: refused, not NaN, amplitudes tending to zero reach the stuck linear limit on every path") {
  // Below uy every friction element sticks and the Yeoh spring is 2 D10 (eq. 3.3): K* is that
  // of the linear network, nested chains included.
  const auto net = test::network_from(R"(
    model z {
      yeoh rubber (D10 = 20, D20 = -0.5, D30 = 0.01)
      maxwell m (k = 15, tau = 4 ms)
      friction f (k = 50, uy = 2 um)
      series { spring s (k = 30) friction g (k = 40, uy = 3 um) }
    })",
                                      "z");
  const auto linear = test::network_from(R"(
    model l {
      spring rubber (k = 40)
      maxwell m (k = 15, tau = 4 ms)
      spring f (k = 50)
      series { spring s (k = 30) spring g (k = 40) }
    })",
                                         "l");
  CHECK_THROWS_WITH_AS(stepped(net, 0.0, 5.0, runtime::SolverChoice::fixed),
                       doctest::Contains("positive, finite amplitude and frequency, got 0 mm and 5 Hz"), std::logic_error);
  CHECK_THROWS_AS(runtime::simulate_harmonic_point(net, std::nan(""), 5.0, {}), std::logic_error);
  for (double f : {0.5, 20.0}) {
    const auto k_star = runtime::complex_stiffness(linear.model(), linear.parameters(), f);
    REQUIRE(k_star);
    for (double u0 : {1e-4, 1e-9}) {
      CAPTURE(f);
      CAPTURE(u0);
      check_close(stepped(net, u0, f, runtime::SolverChoice::fixed), *k_star, 1e-3, 1e-3);  // first order behind a node
      check_close(stepped(net, u0, f, runtime::SolverChoice::sundials), *k_star, 1e-5, 1e-5);
    }
  }
}

TEST_CASE("a parameter whose best value lies beyond its bound ends on the bound, and the others are still found") {
  const auto truth = test::network_from("model t { spring e (k = 100) maxwell m (k = 60, tau = 5 ms) }", "t");
  const auto data = harmonic_data_of(truth, {0.5}, {1, 5, 10, 20, 40, 80}, {});
  // The Maxwell stiffness may not exceed 40 (truth 60).
  const auto start = test::network_from(
      "model t { spring e (k = 150 in [10, 1000]) maxwell m (k = 20 in [1, 40], tau = 2 ms in [0.1 ms, 100 ms]) }", "t");
  const auto result = runtime::fit(start, runtime::bounded_parameters(start), {data}, {});
  CHECK(result.network.parameter(1) == doctest::Approx(40.0).epsilon(1e-9));
  CHECK(std::isfinite(result.err));
  CHECK(result.err > 0.0);
}

TEST_CASE("a fit that starts with every parameter on a bound still finds the truth inside") {
  const auto truth = test::network_from("model t { spring e (k = 100) maxwell m (k = 60, tau = 5 ms) }", "t");
  const auto data = harmonic_data_of(truth, {0.5}, {1, 5, 10, 20, 40, 80}, {});
  const auto start = test::network_from(
      "model t { spring e (k = 10 in [10, 1000]) maxwell m (k = 1000 in [1, 1000], tau = 0.1 ms in [0.1 ms, 100 ms]) }", "t");
  const auto result = runtime::fit(start, runtime::bounded_parameters(start), {data}, {});
  CHECK(result.network.parameter(0) == doctest::Approx(100.0).epsilon(1e-4));
  CHECK(result.network.parameter(1) == doctest::Approx(60.0).epsilon(1e-4));
  CHECK(result.network.parameter(2) == doctest::Approx(5e-3).epsilon(1e-4).scale(0.0));
  CHECK(result.err < 1e-6);
}

TEST_CASE("a fit with more free parameters than residuals matches the data and says why it has no standard errors") {
  const auto truth = test::network_from("model t { spring e (k = 100) maxwell m (k = 60, tau = 5 ms) }", "t");
  const auto data = harmonic_data_of(truth, {0.5}, {10}, {});  // 2 residuals, 3 free parameters
  const auto start = test::network_from(
      "model t { spring e (k = 50 in [10, 1000]) maxwell m (k = 20 in [1, 1000], tau = 2 ms in [0.1 ms, 100 ms]) }", "t");
  const auto result = runtime::fit(start, runtime::bounded_parameters(start), {data}, {});
  CHECK(result.err < 1e-8);
  CHECK(result.statistics.rank == 2);
  CHECK(std::count(result.statistics.identifiable.begin(), result.statistics.identifiable.end(), true) == 0);
  REQUIRE(!result.notes.empty());
  CHECK(result.notes.back() ==
        "no standard errors: 2 residuals for 2 identifiable directions leave no degree of freedom to estimate "
        "the noise; add data points or fix parameters");
}

TEST_CASE("a fit with a fixed seed repeats bit for bit, on one thread, two or three") {
  const auto truth = test::network_from("model t { spring e (k = 100) maxwell m (k = 60, tau = 5 ms) friction f (k = 80, uy = 0.05 mm) }", "t");
  const auto data = harmonic_data_of(truth, {0.1, 1.0}, {1, 10, 40}, {});
  const auto start = test::network_from(
      "model t { spring e (k = 30 in [1, 1000]) maxwell m (k = 20 in [1, 1000], tau = 1 ms in [0.1 ms, 100 ms]) "
      "friction f (k = 30 in [1, 1000], uy = 0.2 mm in [1 um, 1 mm]) }",
      "t");
  runtime::FitSettings settings;
  settings.search.max_evaluations = 600;
  settings.search.seed = 7;
  const auto a = runtime::fit(start, runtime::bounded_parameters(start), {data}, settings);
  const auto b = runtime::fit(start, runtime::bounded_parameters(start), {data}, settings);
  CHECK(a.evaluations == b.evaluations);
  CHECK(a.objective == b.objective);
  CHECK(a.network.parameters() == b.network.parameters());
  // On several threads the Jacobians' columns and the samples are evaluated side by side
  // (search_tracker.hpp): the same evaluations, recorded in the same order.
  for (const int threads : {2, 3}) {
    CAPTURE(threads);
    settings.score.harmonic.threads = threads;
    const auto c = runtime::fit(start, runtime::bounded_parameters(start), {data}, settings);
    CHECK(c.evaluations == a.evaluations);
    CHECK(c.objective == a.objective);
    CHECK(c.err == a.err);
    CHECK(c.status == a.status);
    CHECK(c.network.parameters() == a.network.parameters());
    CHECK(c.statistics.standard_error == a.statistics.standard_error);
  }
}

}  // namespace numerics_edges_test
