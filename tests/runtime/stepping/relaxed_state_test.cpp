// The relaxed start (#25 item 1) against hand solutions: root-parallel networks, springs in
// series, a yeoh spring in series, a gap's play, free members; from 0 the rest state; the first
// steps after it in closed form; and the fixed-step and IDA paths from the same start.
#include "runtime/stepping/relaxed_state.hpp"

#include "runtime/core/drive.hpp"
#include "runtime/protocols/run_history.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace relaxed_state_test {

using namespace rheo;

namespace {

// Force [N] and elongation [mm] of each element at sample 0 of a history from u0.
runtime::History start_of(const runtime::Network& network, double u0, lang::SolverChoice solver = lang::SolverChoice::fixed) {
  runtime::Drive drive{{0.0, 0.01}, {u0, u0}};
  return runtime::run_history(network, drive, true, solver);
}

double element(const runtime::History& h, const std::string& path, bool force, std::size_t sample = 0) {
  for (std::size_t i = 0; i < h.element_paths.size(); ++i)
    if (h.element_paths[i] == path) return (force ? h.element_force : h.element_elongation)[i][sample];
  FAIL("no element " << path);
  return 0.0;
}

}  // namespace

TEST_CASE("relaxed at u0, a root-parallel network carries only its elastic springs' force, Maxwell and friction start unloaded") {
  const auto net = test::network_from(
      "model m { spring s (k = 120 N/mm)\n yeoh y (D10 = 80 N/mm, D20 = -2 N/mm^3, D30 = 0.3 N/mm^5)\n maxwell m1 (k = 50 N/mm, tau = 10 ms)\n"
      "friction f (k = 400 N/mm, uy = 0.05 mm)\n slider l (fy = 7 N)\n dashpot d (c = 2 N*s/mm) }",
      "m");
  const double u0 = 1.3;
  const runtime::State s = runtime::relaxed_state(net, u0);
  const double yeoh = 2.0 * u0 * (80.0 + 2.0 * -2.0 * u0 * u0 + 3.0 * 0.3 * std::pow(u0, 4));  // eq. 3.3
  CHECK(s.force == doctest::Approx(120.0 * u0 + yeoh).epsilon(1e-14));
  for (double v : s.values) CHECK(v == 0.0);
  // One step on: du = 0.2 mm over dt = 0.1 s. Maxwell from 0: c (du/dt)(1 - exp(-dt/tau)) (exact for
  // a ramp); friction from 0: k du capped at fy = 20 N; slider at fy; dashpot c du/dt.
  const runtime::Drive drive{{0.0, 0.1}, {u0, u0 + 0.2}};
  const auto h = runtime::run_history(net, drive, true);
  CHECK(h.force[0] == doctest::Approx(120.0 * u0 + yeoh).epsilon(1e-14));
  CHECK(element(h, "m1", true, 1) == doctest::Approx(0.5 * 2.0 * (1.0 - std::exp(-10.0))).epsilon(1e-12).scale(0.0));
  CHECK(element(h, "f", true, 1) == doctest::Approx(20.0).epsilon(1e-14));
  CHECK(element(h, "l", true, 1) == doctest::Approx(7.0).epsilon(1e-14));
  CHECK(element(h, "d", true, 1) == doctest::Approx(4.0).epsilon(1e-12));
}

TEST_CASE("from displacement 0 the relaxed state is the rest state, bit for bit") {
  const auto net = test::network_from(
      "model m { spring s (k = 1 N/mm)\n series c { spring a (k = 2 N/mm)\n gap g (width = 0.2 mm) }\n series d { friction f (k = 3 N/mm, uy = 0.1 mm)\n "
      "spring b (k = 5 N/mm) } }",
      "m");
  const runtime::State relaxed = runtime::relaxed_state(net, 0.0), rest = runtime::Simulator(net).rest_state();
  CHECK(relaxed.values == rest.values);
  CHECK(relaxed.force == 0.0);
  CHECK(relaxed.u == 0.0);
}

TEST_CASE("springs in series share the force by their compliances, a yeoh spring in series carries the same force") {
  const auto net = test::network_from(
      "model m { series a { spring k1 (k = 300 N/mm)\n spring k2 (k = 600 N/mm) }\n"
      "series b { spring k3 (k = 50 N/mm)\n yeoh y (D10 = 20 N/mm, D20 = 3 N/mm^3, D30 = 0.5 N/mm^5) } }",
      "m");
  const double u0 = 0.9;
  const auto h = start_of(net, u0);
  CHECK(element(h, "a.k1", true) == doctest::Approx(200.0 * u0).epsilon(1e-12));  // 1/(1/300 + 1/600) = 200 N/mm
  CHECK(element(h, "a.k1", false) == doctest::Approx(u0 * 2.0 / 3.0).epsilon(1e-12).scale(0.0));
  CHECK(element(h, "a.k2", false) == doctest::Approx(u0 / 3.0).epsilon(1e-12).scale(0.0));
  // Chain b: F = 50 e_k3 = yeoh(e_y), e_k3 + e_y = u0.
  const double f = element(h, "b.k3", true), e_y = element(h, "b.y", false);
  CHECK(f == doctest::Approx(test::yeoh_force(20.0, 3.0, 0.5, e_y)).epsilon(1e-12));
  CHECK(element(h, "b.k3", false) + e_y == doctest::Approx(u0).epsilon(1e-12).scale(0.0));
  CHECK(f / 50.0 == doctest::Approx(element(h, "b.k3", false)).epsilon(1e-12).scale(0.0));
  CHECK(h.force[0] == doctest::Approx(200.0 * u0 + f).epsilon(1e-12));
}

TEST_CASE("a gap takes its play first, and a free member in a chain leaves the chain unloaded") {
  const auto net = test::network_from(
      "model m { series a { spring k1 (k = 100 N/mm)\n gap g (width = 0.6 mm) }\n"
      "series b { friction f (k = 40 N/mm, uy = 0.1 mm)\n spring k2 (k = 70 N/mm) }\n"
      "series c { spring k3 (k = 90 N/mm)\n maxwell m (k = 10 N/mm, tau = 1 s) } }",
      "m");
  SUBCASE("beyond the play: the gap at its stop, the spring the rest") {
    const auto h = start_of(net, -0.8);
    CHECK(element(h, "a.g", false) == doctest::Approx(-0.3).epsilon(1e-14).scale(0.0));
    CHECK(element(h, "a.k1", true) == doctest::Approx(-50.0).epsilon(1e-12));
    CHECK(h.force[0] == doctest::Approx(-50.0).epsilon(1e-12));
    CHECK(element(h, "b.f", true) == 0.0);
    CHECK(element(h, "b.f", false) == doctest::Approx(-0.8).epsilon(1e-14).scale(0.0));
    CHECK(element(h, "b.k2", false) == 0.0);
    CHECK(element(h, "c.m", false) == doctest::Approx(-0.8).epsilon(1e-14).scale(0.0));
  }
  SUBCASE("within the play: nothing carries force") {
    const auto h = start_of(net, 0.25);
    CHECK(h.force[0] == 0.0);
    CHECK(element(h, "a.g", false) == doctest::Approx(0.25).epsilon(1e-14).scale(0.0));
    CHECK(element(h, "a.k1", false) == 0.0);
  }
}

TEST_CASE("a relaxed start: fixed steps and IDA agree on a nested network over a history") {
  const auto net = test::network_from(
      "model m { spring s (k = 100 N/mm)\n maxwell m1 (k = 50 N/mm, tau = 20 ms)\n friction f1 (k = 200 N/mm, uy = 0.05 mm)\n"
      "series a { spring k3 (k = 300 N/mm)\n yeoh y (D10 = 100 N/mm, D20 = 1 N/mm^3, D30 = 0.1 N/mm^5) }\n"
      "series b { spring k5 (k = 100 N/mm)\n gap g (width = 0.6 mm) }\n"
      "series c { friction f6 (k = 100 N/mm, uy = 0.1 mm)\n maxwell m6 (k = 80 N/mm, tau = 5 ms) } }",
      "m");
  runtime::Drive drive;
  for (int k = 0; k <= 400; ++k) {
    const double t = k * 1e-3;
    drive.time.push_back(t);
    drive.displacement.push_back(1.1 + 0.4 * std::sin(2.0 * std::numbers::pi * 5.0 * t));
  }
  const auto fixed = runtime::run_history(net, drive, false, lang::SolverChoice::fixed);
  const auto ida = runtime::run_history(net, drive, false, lang::SolverChoice::sundials);
  double scale = 0.0, worst = 0.0;
  for (double f : fixed.force) scale = std::max(scale, std::abs(f));
  for (std::size_t k = 0; k < fixed.force.size(); ++k) worst = std::max(worst, std::abs(fixed.force[k] - ida.force[k]));
  CHECK(fixed.force[0] == ida.force[0]);
  CHECK(fixed.force[0] > 100.0 * 1.1);  // the elastic springs are loaded at the start
  MESSAGE("largest difference " << worst / scale << " of max |F| " << scale << " N");
  CHECK(worst < 1e-5 * scale);
}

}  // namespace relaxed_state_test
