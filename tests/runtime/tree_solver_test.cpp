// Nested series/parallel subtrees against hand-derived piecewise-linear solutions.
#include "runtime/tree_solver.hpp"

#include "runtime/drives.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>

using namespace rheo;

namespace {
runtime::History ramp(const runtime::Network& net, double to, int steps) {
  runtime::Drive d;
  for (int i = 0; i <= steps; ++i) {
    d.time.push_back(i * 0.01);
    d.displacement.push_back(to * i / steps);
  }
  return runtime::run_history(net, d, false);
}
}  // namespace

TEST_CASE("springs in series: k1 k2 / (k1 + k2)") {
  const auto net = test::network_from("model s { series { spring a (k = 300) spring b (k = 600) } }", "s");
  const auto h = ramp(net, 1.0, 10);
  for (std::size_t i = 0; i < h.time.size(); ++i) CHECK(std::abs(h.force[i] - 200.0 * h.displacement[i]) < 1e-9);
}

TEST_CASE("sliders in series slip at the weakest slip force") {
  const auto net = test::network_from("model s { spring e (k = 1) series { slider a (fy = 7) slider b (fy = 3) } }", "s");
  const auto h = ramp(net, 2.0, 8);
  for (std::size_t i = 1; i < h.time.size(); ++i) CHECK(std::abs(h.force[i] - (h.displacement[i] + 3.0)) < 1e-12);
}

TEST_CASE("spring in series with a parallel spring + friction block") {
  // Elastic: F = k0 (k1 + k2) / (k0 + k1 + k2) u until k2 e_p = fy; then F = k0 (u - e_p) with
  // e_p = (k0 u - fy) / (k0 + k1).
  const double k0 = 200, k1 = 50, k2 = 150, fy = 3;
  const auto net = test::network_from("model s { series { spring a (k = 200) parallel { spring b (k = 50) friction f (k = 150, fy = 3) } } }", "s");
  const auto h = ramp(net, 0.2, 40);
  for (std::size_t i = 0; i < h.time.size(); ++i) {
    const double u = h.displacement[i];
    const double elastic = k0 * (k1 + k2) / (k0 + k1 + k2) * u;
    const double ep_elastic = elastic / (k1 + k2);
    const double f = k2 * ep_elastic <= fy ? elastic : k0 * (u - (k0 * u - fy) / (k0 + k1));
    CHECK(std::abs(h.force[i] - f) < 1e-9);
  }
}

TEST_CASE("spring in series with a parallel slider + spring block (rigid until it slips)") {
  const double k0 = 100, k1 = 20, fy = 5;
  const auto net = test::network_from("model s { series { spring a (k = 100) parallel { slider s (fy = 5) spring b (k = 20) } } }", "s");
  const auto h = ramp(net, 0.3, 30);
  for (std::size_t i = 0; i < h.time.size(); ++i) {
    const double u = h.displacement[i];
    const double f = k0 * u <= fy ? k0 * u : k0 * (u - (k0 * u - fy) / (k0 + k1));
    CHECK(std::abs(h.force[i] - f) < 1e-9);
  }
}

TEST_CASE("two friction elements in series act as one with k = k1 k2/(k1 + k2) and fy = min") {
  const auto chain = test::network_from("model s { series { friction a (k = 300, fy = 9) friction b (k = 600, fy = 4) } }", "s");
  const auto single = test::network_from("model s { friction a (k = 200, fy = 4) }", "s");
  const auto drive = runtime::quasistatic_sine({0.1, 0.03}, 1.0, 2, 64);
  const auto a = runtime::run_history(chain, drive, false), b = runtime::run_history(single, drive, false);
  for (std::size_t i = 0; i < a.time.size(); ++i) CHECK(std::abs(a.force[i] - b.force[i]) < 1e-9);
}
