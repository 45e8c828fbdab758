// The describing-function cold start of the event path's shooting (pwl_describing.hpp): the
// first harmonic of a Jenkins element's exact slip (against the event path's own periodic state),
// no start where the slider never slips or the branch is not served, and on a grid the same
// periodic states as a start from rest, in fewer cycles than the stuck linear start's.
#include "runtime/closed_form/pwl_describing.hpp"
#include "runtime/closed_form/pwl_periodic.hpp"
#include "runtime/io/fit_data.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <numbers>
#include <string>

namespace pwl_describing_test {

using namespace rheo;

namespace {

runtime::PwlBranch branch_of(const runtime::Network& net) {
  runtime::PwlBranch branch;
  REQUIRE(runtime::PwlBranch::build(net, net.topology().subtrees[0], branch));
  return branch;
}

}  // namespace

TEST_CASE("a spring before a slider: the describing start is the first harmonic of the exact slip") {
  // Quasi-static: the slider sees the spring alone, Z = k, and the branch is a Jenkins element
  // exactly. Its node sits at the slider's elongation x = u - F/k; the event path's periodic
  // force gives x's first harmonic by quadrature, x(0) its cosine part, x'(0) w times its sine part.
  const double k = 200.0, fy = 20.0;
  const auto net = test::network_from("model j { series s { spring a (k = 200 N/mm)\n slider c (fy = 20 N) } }", "j");
  const runtime::PwlBranch branch = branch_of(net);
  REQUIRE(branch.internal_nodes == 1);
  for (double u0 : {0.15, 0.5, 3.0}) {
    const double f = 2.0, omega = 2.0 * std::numbers::pi * f;
    runtime::PwlPeriodicState exact;
    REQUIRE(exact.solve(branch, u0, omega));
    constexpr int samples = 4096;
    double cosine = 0.0, sine = 0.0;
    for (int j = 0; j < samples; ++j) {
      const double theta = 2.0 * std::numbers::pi * j / samples;
      const double x = u0 * std::sin(theta) - exact.force(theta) / k;
      cosine += 2.0 * x * std::cos(theta) / samples, sine += 2.0 * x * std::sin(theta) / samples;
    }
    runtime::PwlVector X0;
    REQUIRE(runtime::pwl_describing_start(branch, u0, omega, X0));
    CAPTURE(u0);
    // The quadrature of a kinked periodic function by 4096 samples: within 1e-6 of u0.
    CHECK(std::abs(X0[0] - cosine) < 1e-6 * u0);
    CHECK(std::abs(X0[1] - omega * sine) < 1e-6 * u0 * omega);
  }
  // Where the stuck force stays below the cap (k u0 <= fy) no start is given.
  runtime::PwlVector X0;
  CHECK_FALSE(runtime::pwl_describing_start(branch, 0.9 * fy / k, 10.0, X0));
}

TEST_CASE("the describing start serves one slider with even caps, without gaps") {
  runtime::PwlVector X0;
  const auto two = test::network_from("model t { series s { friction f1 (k = 400 N/mm, uy = 0.1 mm)\n friction f2 (k = 100 N/mm, uy = 0.2 mm) } }",
                                      "t");
  CHECK_FALSE(runtime::pwl_describing_start(branch_of(two), 1.0, 10.0, X0));
  const auto gap = test::network_from("model g { series s { gap g (width = 0.2 mm)\n slider c (fy = 5 N)\n spring a (k = 100 N/mm) } }", "g");
  CHECK_FALSE(runtime::pwl_describing_start(branch_of(gap), 1.0, 10.0, X0));
  const auto uneven = test::network_from("model u { series s { slider c (fy_pos = 10 N, fy_neg = 5 N)\n spring a (k = 100 N/mm) } }", "u");
  CHECK_FALSE(runtime::pwl_describing_start(branch_of(uneven), 1.0, 10.0, X0));
}

namespace {

// Every point of GRID on the subtree of NET: the cold solve (the describing start where it
// applies) against a solve started from rest, every slider stuck; returns the cycles a point.
double check_grid(const runtime::Network& net, const runtime::HarmonicData& grid) {
  const runtime::PwlBranch branch = branch_of(net);
  runtime::PwlStart rest;
  rest.X0 = runtime::PwlVector::Zero(2 * branch.internal_nodes);
  rest.mode.assign(branch.switches.size(), 0);
  int cycles = 0;
  for (std::size_t i = 0; i < grid.size(); ++i) {
    const double u0 = grid.amplitude[i], omega = 2.0 * std::numbers::pi * grid.frequency[i];
    runtime::PwlPeriodicState cold, from_rest;
    REQUIRE(cold.solve(branch, u0, omega));
    REQUIRE(from_rest.solve(branch, u0, omega, &rest));
    cycles += cold.cycles();
    CAPTURE(u0);
    CAPTURE(grid.frequency[i]);
    // Both to the shooting's tolerance (1e-11 on the scaled state).
    const double scale = std::hypot(from_rest.storage(), from_rest.loss());
    CHECK(std::abs(cold.storage() - from_rest.storage()) < 1e-9 * scale);
    CHECK(std::abs(cold.loss() - from_rest.loss()) < 1e-9 * scale);
  }
  return static_cast<double>(cycles) / static_cast<double>(grid.size());
}

runtime::HarmonicData example_grid(const std::string& csv) {
  return runtime::read_fit_data(std::string(RHEO_DATA_DIR) + "/" + csv, 1.0).harmonic();
}

}  // namespace

TEST_CASE("the describing start reaches the periodic states a start from rest reaches, in fewer cycles") {
  // The hydrobushing's fluid column (examples/hydrobushing_fit.rheo block 2's start values) on
  // its 147 points: the stuck linear start took 3.76 cycles a point (552 in all).
  const auto fluid = test::network_from(R"(
    model fluid { series f { slider cap (fy = 50 N)
                             spring k1 (k = 500 N/mm)
                             parallel y { inerter column (b = 30 kg)
                                          dashpot channel (c = 2 N*s/mm)
                                          spring bulge (k = 200 N/mm) } } })",
                                        "fluid");
  const double fluid_cycles = check_grid(fluid, example_grid("hydrobushing_harmonic.csv"));
  MESSAGE("fluid column: " << fluid_cycles << " cycles a point");
  CHECK(fluid_cycles < 3.5);
  // A slider before a Maxwell arm (examples/coupled_bushing_fit.rheo's, at its start values).
  const auto arm = test::network_from(R"(
    model arm { series a { slider s (fy = 10 N)
                           maxwell m (k = 300 N/mm, tau = 20 ms) } })",
                                      "arm");
  const double arm_cycles = check_grid(arm, example_grid("coupled_bushing_harmonic.csv"));
  MESSAGE("slider and Maxwell arm: " << arm_cycles << " cycles a point");
}

}  // namespace pwl_describing_test
