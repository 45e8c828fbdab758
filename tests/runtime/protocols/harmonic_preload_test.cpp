// Harmonic points about a preload p (#25 item 3), u = p + u0 sin(w t): the yeoh spring's tangent
// stiffness at p in the small-amplitude limit, (max F - min F)/2 of Y(p + u0 sin) against a
// dense sampling, the closed form against time stepping and IDA, shift invariance of networks
// without yeoh springs and gaps, and a gap's play seen from a preload.
#include "runtime/protocols/harmonic.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace harmonic_preload_test {

using namespace rheo;
using runtime::HarmonicOptions;
using runtime::SteadyState;

namespace {

HarmonicOptions with(SteadyState steady_state, lang::SolverChoice solver = lang::SolverChoice::automatic,
                     runtime::HarmonicDefinition definition = runtime::HarmonicDefinition::thesis) {
  HarmonicOptions o;
  o.steady_state = steady_state;
  o.solver = solver;
  o.definition = definition;
  return o;
}

constexpr double D10 = 389.43, D20 = -2.1094, D30 = 0.0786;  // specimen D's rubber (Table D.4), N/mm, N/mm^3, N/mm^5
const char* const kYeoh = "model y { yeoh r (D10 = 389.43 N/mm, D20 = -2.1094 N/mm^3, D30 = 0.0786 N/mm^5) }";

}  // namespace

TEST_CASE("a yeoh spring about a preload: at small amplitude the dynamic stiffness is its tangent at p, Y'(p)") {
  const auto net = test::network_from(kYeoh, "y");
  for (double p : {-3.0, 0.0, 1.5, 4.0}) {
    const double tangent = 2.0 * D10 + 12.0 * D20 * p * p + 30.0 * D30 * p * p * p * p;
    for (auto definition : {runtime::HarmonicDefinition::thesis, runtime::HarmonicDefinition::first_harmonic}) {
      const auto point = runtime::simulate_harmonic_point(net, 1e-4, 10.0,
                                                          with(SteadyState::closed_form, lang::SolverChoice::automatic, definition), p);
      CAPTURE(p);
      CHECK(point.preload == p);
      CHECK(test::relative_error(point.measures.stiffness, tangent) < 1e-7);  // O((u0/p)^2) from the curvature
      CHECK(std::abs(point.measures.phase) < 1e-12);
    }
  }
}

TEST_CASE("a yeoh spring about a preload: the thesis stiffness is (max F - min F)/2u0 over the cycle, the first harmonic its odd part") {
  const auto net = test::network_from(kYeoh, "y");
  auto force = [](double u) { return test::yeoh_force(D10, D20, D30, u); };  // eq. 3.3
  const double p = 2.5, u0 = 1.7;
  double highest = -1e300, lowest = 1e300, sine_sum = 0.0;
  const int n = 1 << 20;
  for (int k = 0; k < n; ++k) {
    const double theta = 2.0 * std::numbers::pi * (k + 0.5) / n;
    const double f = force(p + u0 * std::sin(theta));
    highest = std::max(highest, f), lowest = std::min(lowest, f);
    sine_sum += f * std::sin(theta);
  }
  const auto thesis = runtime::simulate_harmonic_point(net, u0, 3.0, with(SteadyState::closed_form), p);
  CHECK(test::relative_error(thesis.measures.stiffness, (highest - lowest) / (2.0 * u0)) < 1e-9);
  const auto first = runtime::simulate_harmonic_point(
      net, u0, 3.0, with(SteadyState::closed_form, lang::SolverChoice::automatic, runtime::HarmonicDefinition::first_harmonic), p);
  CHECK(test::relative_error(first.measures.stiffness, 2.0 * sine_sum / n / u0) < 1e-9);  // midpoint rule: exact for a trigonometric polynomial
  // Without a preload the loop is odd: the same (max - min)/2 is max F.
  CHECK(test::relative_error(runtime::simulate_harmonic_point(net, u0, 3.0, with(SteadyState::closed_form), 0.0).measures.stiffness,
                             force(u0) / u0) < 1e-12);
}

TEST_CASE("preloaded specimen D (yeoh, Maxwell, frictions): the closed form is the limit of time stepping, and IDA agrees") {
  const auto net = test::network_from(
      "model d { yeoh r (D10 = 389.43 N/mm, D20 = -2.1094 N/mm^3, D30 = 0.0786 N/mm^5)\n maxwell m1 (k = 61.476 N/mm, tau = 4.335 ms)\n"
      " friction f1 (k = 1016.6 N/mm, uy = 101.58 um)\n friction f2 (k = 301.04 N/mm, uy = 42.256 um) }",
      "d");
  for (double p : {1.0, -2.0}) {
    for (double u0 : {0.2, 1.0}) {
      const auto closed = runtime::simulate_harmonic_point(net, u0, 7.0, with(SteadyState::closed_form), p);
      HarmonicOptions fine = with(SteadyState::time_stepping);
      fine.steps_per_cycle = 8192;
      const auto stepped = runtime::simulate_harmonic_point(net, u0, 7.0, fine, p);
      const auto ida = runtime::simulate_harmonic_point(net, u0, 7.0, with(SteadyState::automatic, lang::SolverChoice::sundials), p);
      CAPTURE(p);
      CAPTURE(u0);
      CHECK(stepped.converged);
      CHECK(ida.converged);
      CHECK(test::relative_error(stepped.measures.stiffness, closed.measures.stiffness) < 2e-6);
      CHECK(std::abs(test::degrees(stepped.measures.phase - closed.measures.phase)) < 1e-3);
      CHECK(test::relative_error(ida.measures.stiffness, closed.measures.stiffness) < 2e-6);
      CHECK(std::abs(test::degrees(ida.measures.phase - closed.measures.phase)) < 1e-3);
      // The preload matters here: the rubber's tangent changes by 12 D20 p^2 + 30 D30 p^4.
      const auto centred = runtime::simulate_harmonic_point(net, u0, 7.0, with(SteadyState::closed_form), 0.0);
      CHECK(test::relative_error(closed.measures.stiffness, centred.measures.stiffness) > 1e-3);
    }
  }
}

TEST_CASE("without yeoh springs or gaps a preload changes nothing but a constant force: every path gives p = 0's stiffness and phase") {
  const auto net = test::network_from(
      "model s { spring k (k = 200 N/mm)\n maxwell m (k = 80 N/mm, tau = 20 ms)\n friction f (k = 300 N/mm, uy = 0.05 mm)\n"
      " series c { friction g (k = 150 N/mm, uy = 0.1 mm)\n maxwell n (k = 60 N/mm, tau = 5 ms) } }",
      "s");
  for (auto options : {with(SteadyState::automatic), with(SteadyState::time_stepping), with(SteadyState::automatic, lang::SolverChoice::sundials)}) {
    const auto centred = runtime::simulate_harmonic_point(net, 0.4, 12.0, options, 0.0);
    const auto preloaded = runtime::simulate_harmonic_point(net, 0.4, 12.0, options, 3.0);
    CHECK(test::relative_error(preloaded.measures.stiffness, centred.measures.stiffness) < 1e-6);
    CHECK(std::abs(test::degrees(preloaded.measures.phase - centred.measures.phase)) < 1e-4);
  }
}

TEST_CASE("a gap's play is fixed in space: from a preload past it the branch is engaged, and time stepping and IDA agree") {
  const auto net = test::network_from("model g { spring k (k = 100 N/mm)\n series c { spring s (k = 400 N/mm)\n gap g (width = 1 mm) } }", "g");
  const auto centred = runtime::simulate_harmonic_point(net, 0.2, 5.0, with(SteadyState::automatic), 0.0);
  CHECK(test::relative_error(centred.measures.stiffness, 100.0) < 1e-9);  // within the play: the branch never engages
  const auto stepped = runtime::simulate_harmonic_point(net, 0.2, 5.0, with(SteadyState::automatic), 1.0);
  const auto ida = runtime::simulate_harmonic_point(net, 0.2, 5.0, with(SteadyState::automatic, lang::SolverChoice::sundials), 1.0);
  CHECK(test::relative_error(stepped.measures.stiffness, 500.0) < 1e-6);  // past the play at p = 1 > 0.5 + 0.2: both springs
  CHECK(test::relative_error(ida.measures.stiffness, 500.0) < 1e-6);
}

}  // namespace harmonic_preload_test
