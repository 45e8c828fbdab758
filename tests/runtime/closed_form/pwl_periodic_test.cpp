// The event-driven periodic state of piecewise-linear subtrees (pwl_periodic.hpp) against
// independent paths: the phasor K* of the same network when no slider ever slips, the
// fixed-step kernels Richardson-extrapolated to N -> infinity, and IDA.
#include "runtime/closed_form/pwl_periodic.hpp"
#include "runtime/closed_form/periodic_closed_form.hpp"
#include "runtime/protocols/harmonic.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <algorithm>
#include <numbers>
#include <tuple>
#include <utility>
#include <vector>

namespace pwl_periodic_test {

using namespace rheo;
using runtime::HarmonicDefinition;

namespace {

// The hydrobushing's fluid branch (examples/hydrobushing.rheo) with a cap of `fy` N.
std::string fluid_branch(double fy) {
  return "model fluid { series f { slider cap (fy = " + std::to_string(fy) +
         " N)\n spring k1 (k = 600 N/mm)\n parallel y { inerter column (b = 40 kg)\n dashpot channel (c = 3.0 N*s/mm)\n"
         " spring bulge (k = 150 N/mm) } } }";
}

const char* kLinearFluid = R"(
  model fluid { series f { spring k1 (k = 600 N/mm)
    parallel y { inerter column (b = 40 kg)
                 dashpot channel (c = 3.0 N*s/mm)
                 spring bulge (k = 150 N/mm) } } })";

}  // namespace

TEST_CASE("a slider that never slips leaves the branch's linear K*") {
  const auto capped = test::network_from(fluid_branch(1e7), "fluid");
  const auto linear = test::network_from(kLinearFluid, "fluid");
  REQUIRE(runtime::has_closed_form_periodic_state(capped));
  for (double f : {1.0, 11.0, 21.0, 40.0}) {
    for (auto definition : {HarmonicDefinition::thesis, HarmonicDefinition::first_harmonic}) {
      const auto a = runtime::closed_form_harmonic_point(capped, 0.1, f, definition);
      const auto b = runtime::closed_form_harmonic_point(linear, 0.1, f, definition);
      CAPTURE(f);
      CHECK(test::relative_error(a.measures.stiffness, b.measures.stiffness) < 1e-10);
      CHECK(std::abs(a.measures.phase - b.measures.phase) < 1e-10);
    }
  }
}

namespace {

runtime::HarmonicPoint stepped(const runtime::Network& net, double u0, double f, int steps) {
  runtime::HarmonicOptions options;
  options.steady_state = runtime::SteadyState::time_stepping;
  options.solver = runtime::SolverChoice::fixed;
  options.steps_per_cycle = steps;
  options.tolerance = 1e-10;
  options.max_cycles = 20000;
  return runtime::simulate_harmonic_point(net, u0, f, options);
}

// The fixed-step result at N = 1024 and 4096 steps per cycle extrapolated to N -> infinity
// (Richardson, for a path of the given order in the step: first where a dashpot sits behind an
// internal node, second otherwise; docs/numerics.md), against the event-driven state:
// stiffness relative and phase [rad] within `tolerance`, which is well below the error at 1024.
void check_against_time_stepping(const runtime::Network& net, double u0, double f, int order, double tolerance) {
  const auto exact = runtime::closed_form_harmonic_point(net, u0, f, HarmonicDefinition::thesis);
  const auto coarse = stepped(net, u0, f, 1024), fine = stepped(net, u0, f, 4096);
  CAPTURE(u0);
  CAPTURE(f);
  REQUIRE(coarse.converged);
  REQUIRE(fine.converged);
  const double gain = std::pow(4.0, order);
  const double k = (gain * fine.measures.stiffness - coarse.measures.stiffness) / (gain - 1.0);
  const double phase = (gain * fine.measures.phase - coarse.measures.phase) / (gain - 1.0);
  CAPTURE(exact.measures.stiffness);
  CAPTURE(coarse.measures.stiffness);
  CAPTURE(k);
  CHECK(test::relative_error(exact.measures.stiffness, k) < tolerance);
  CHECK(std::abs(exact.measures.phase - phase) < tolerance);
}

}  // namespace

TEST_CASE("the hydrobushing's slider-capped fluid column against time stepping, stuck, slipping and at resonance") {
  const auto net = test::network_from(fluid_branch(60.0), "fluid");
  REQUIRE(runtime::has_closed_form_periodic_state(net));
  for (double u0 : {0.1, 0.5, 2.0})
    for (double f : {1.0, 5.0, 23.0}) check_against_time_stepping(net, u0, f, 1, 1e-5);
}

TEST_CASE("a slider in series with a Maxwell arm: the slipping mode drifts (a zero eigenvalue), in closed form") {
  const auto net = test::network_from(R"(
    model coupled {
      spring k0 (k = 200 N/mm)
      series arm { slider s (fy = 45 N)
                   maxwell m (k = 300 N/mm, tau = 20 ms) }
    })",
                                      "coupled");
  runtime::PwlBranch branch;
  REQUIRE(runtime::PwlBranch::build(net, net.topology().subtrees[0], branch));
  runtime::PwlModeSystem slipping;
  REQUIRE(runtime::build_pwl_mode(branch, runtime::PwlModeCode{1}, 10.0, slipping));
  CHECK(slipping.modal);  // the drift is the modal closed form at lambda = 0
  for (double u0 : {0.05, 0.3, 1.5})
    for (double f : {0.5, 5.0, 40.0}) check_against_time_stepping(net, u0, f, 2, 1e-6);
}

TEST_CASE("a spring behind a gap: F = k (|u| - w/2) sgn u beyond contact") {
  const double k = 400.0, width = 0.3;
  const auto net = test::network_from("model g { series c { gap play (width = 0.3 mm)\n spring k (k = 400 N/mm) } }", "g");
  REQUIRE(runtime::has_closed_form_periodic_state(net));
  for (double u0 : {0.2, 0.5, 2.0}) {
    const auto thesis = runtime::closed_form_harmonic_point(net, u0, 3.0, HarmonicDefinition::thesis);
    CAPTURE(u0);
    CHECK(std::abs(thesis.measures.stiffness - k * std::max(0.0, 1.0 - 0.5 * width / u0)) < 1e-9 * k);
    CHECK(std::abs(thesis.measures.phase) < 1e-9);
    // First harmonic by the midpoint rule over 20000 phases (the loop has two kinks per half).
    const auto first = runtime::closed_form_harmonic_point(net, u0, 3.0, HarmonicDefinition::first_harmonic);
    const int n = 20000;
    double storage = 0.0;
    for (int j = 0; j < n; ++j) {
      const double theta = 2.0 * std::numbers::pi * (j + 0.5) / n, u = u0 * std::sin(theta);
      storage += k * std::copysign(std::max(0.0, std::abs(u) - 0.5 * width), u) * std::sin(theta);
    }
    storage *= 2.0 / (n * u0);
    CHECK(std::abs(first.measures.storage - storage) < 1e-7 * k);
  }
}

TEST_CASE("a friction element behind a spring is the root friction element of the series stiffness") {
  const auto nested = test::network_from("model n { series c { spring k1 (k = 300 N/mm)\n friction f (k = 600 N/mm, uy = 0.1 mm) } }", "n");
  const auto root = test::network_from("model r { friction f (k = 200 N/mm, uy = 0.3 mm) }", "r");
  REQUIRE(runtime::has_closed_form_periodic_state(nested));
  for (double u0 : {0.2, 0.31, 1.0, 5.0})
    for (auto definition : {HarmonicDefinition::thesis, HarmonicDefinition::first_harmonic}) {
      const auto a = runtime::closed_form_harmonic_point(nested, u0, 2.0, definition);
      const auto b = runtime::closed_form_harmonic_point(root, u0, 2.0, definition);
      CAPTURE(u0);
      CHECK(test::relative_error(a.measures.stiffness, b.measures.stiffness) < 1e-9);
      CHECK(std::abs(a.measures.phase - b.measures.phase) < 1e-9);
    }
}

TEST_CASE("gaps, nested frictions and a gap behind a slider against time stepping") {
  const char* models[] = {
      "model a { spring k0 (k = 100 N/mm)\n series s { gap g (width = 0.4 mm)\n maxwell m (k = 300 N/mm, tau = 10 ms) } }",
      "model a { spring k0 (k = 50 N/mm)\n series s { friction f1 (k = 400 N/mm, uy = 0.1 mm)\n"
      " parallel p { friction f2 (k = 100 N/mm, uy = 0.2 mm)\n maxwell m (k = 80 N/mm, tau = 5 ms) } } }",
      "model a { spring k0 (k = 10 N/mm)\n series s { gap g (width = 0.2 mm)\n slider s (fy = 20 N)\n spring k (k = 300 N/mm) } }"};
  for (const char* model : models) {
    const auto net = test::network_from(model, "a");
    REQUIRE(runtime::has_closed_form_periodic_state(net));
    for (double u0 : {0.05, 0.3, 2.0})
      for (double f : {0.5, 17.0}) check_against_time_stepping(net, u0, f, 2, 1e-5);
  }
}

TEST_CASE("one-sided caps and off-centre gaps against time stepping: F^ = (max F - min F)/2 over the whole cycle") {
  // Uneven laws (PwlBranch::odd false): the full-period map, no half-wave symmetry. Amplitudes
  // where the caps hold, where both slip and where the gap's contacts differ by side.
  const char* models[] = {
      "model a { spring k0 (k = 10 N/mm)\n series s { spring k (k = 300 N/mm)\n friction f (k = 600 N/mm, fy_pos = 40 N, fy_neg = 25 N) } }",
      "model a { spring k0 (k = 100 N/mm)\n series s { gap g (width = 0.4 mm, center = 0.15 mm)\n maxwell m (k = 300 N/mm, tau = 10 ms) } }",
      "model a { spring k0 (k = 30 N/mm)\n series s { gap g (width = 0.6 mm, center = 0.15 mm)\n"
      " friction f (k = 400 N/mm, fy_pos = 13 N, fy_neg = 20 N) } }"};
  for (const char* model : models) {
    const auto net = test::network_from(model, "a");
    const std::string text = model;
    CAPTURE(text);
    runtime::PwlBranch branch;
    REQUIRE(runtime::PwlBranch::build(net, net.topology().subtrees.back(), branch));
    CHECK_FALSE(branch.odd);
    for (double u0 : {0.05, 0.3, 2.0})
      for (double f : {0.5, 17.0}) check_against_time_stepping(net, u0, f, 2, 1e-5);
  }
}

TEST_CASE("a one-sided slider before a Maxwell arm ratchets: the event path finds no fixed point and says so") {
  // Slipping further one way than the other each cycle, the slider and the dashpot drift by the
  // same amount every period: the force is periodic, the positions are not, and the
  // full-period map has no fixed point. The event path declines; the automatic path hands the
  // point to time stepping, whose state does not repeat either: it reports the point as not
  // converged rather than a steady state (a limit of both paths for ratcheting branches).
  const auto net = test::network_from("model a { series arm { slider s (fy_pos = 45 N, fy_neg = 30 N)\n maxwell m (k = 300 N/mm, tau = 20 ms) } }",
                                      "a");
  runtime::PwlBranch branch;
  REQUIRE(runtime::PwlBranch::build(net, net.topology().subtrees[0], branch));
  runtime::PwlPeriodicState state;
  CHECK_FALSE(state.solve(branch, 0.3, 2.0 * std::numbers::pi * 17.0));
  CHECK_FALSE(runtime::try_closed_form_harmonic_point(net, 0.3, 17.0, HarmonicDefinition::thesis).has_value());
  runtime::HarmonicOptions options;
  options.max_cycles = 40;
  CHECK_FALSE(runtime::simulate_harmonic_point(net, 0.3, 17.0, options).converged);
  // Where the caps hold, nothing drifts and the event path answers.
  REQUIRE(state.solve(branch, 0.05, 2.0 * std::numbers::pi * 17.0));
  check_against_time_stepping(net, 0.05, 17.0, 2, 1e-5);
}

TEST_CASE("fluid columns a fit visits: a slider that sticks at the drive's turning point, a heavy column Newton must globalise") {
  // Found by the default-settings fit of examples/hydrobushing_fit.rheo block 2; both used to
  // give up (the first switched stuck <-> slipping without end at t = T/4, the second trapped
  // Newton steps and plain cycles in a loop for 60 cycles) and fall back to IDA.
  struct Case {
    const char* model;
    double u0, f;
  };
  const Case cases[] = {{"model c { series f { slider cap (fy = 10.892557677656269 N)\n spring k1 (k = 1235.1602091455047 N/mm)\n"
                         " parallel y { inerter column (b = 6.6682120427872631 kg)\n dashpot channel (c = 0.76464491253602807 N*s/mm)\n"
                         " spring bulge (k = 90.224264508261996 N/mm) } } }",
                         1.5, 1.0},
                        {"model c { series f { slider cap (fy = 18.558156250335621 N)\n spring k1 (k = 4197.3317102966812 N/mm)\n"
                         " parallel y { inerter column (b = 91.161585658256314 kg)\n dashpot channel (c = 0.45651999449082065 N*s/mm)\n"
                         " spring bulge (k = 74.763684720900741 N/mm) } } }",
                         0.1, 9.0}};
  for (const Case& c : cases) {
    const auto net = test::network_from(c.model, "c");
    const auto point = runtime::try_closed_form_harmonic_point(net, c.u0, c.f, HarmonicDefinition::thesis);
    REQUIRE(point.has_value());
    CHECK(point->cycles <= 12);
    check_against_time_stepping(net, c.u0, c.f, 1, 1e-5);
  }
}

// A stiff, nearly undamped fluid column (below): 2.2e-9 kg behind 1232 N/mm.
constexpr const char* kStiffColumn = R"(
    model col {
      spring s (k = 488.5051437 N/mm)
      series coupled {
        slider cap (fy = 78.07226631 N)
        spring chamber (k = 1231.56657 N/mm)
        parallel column { inerter mass (b = 2.22631e-09 kg)  dashpot channel (c = 1.9885e-12 N*s/mm) }
      }
    })";

// Found by rheo diagnose on a pure-noise grid of the second generator (draw 18): a fluid
// column's refit drove the mass to 2.2e-9 kg behind a 1232 N/mm chamber, an undamped mode at
// 3.7 MHz under a 0.86 Hz drive. The map's Jacobian, in the shooting's scales, has rows of order
// omega_n / omega ~ 1.5e6: the rank-revealing solve dropped the velocity's column and Newton's
// step stayed at zero, and rounding in the positions alone left 1e-10 in that velocity, above
// the periodic test's 1e-11; the point fell back to IDA, which took minutes to step the mode.
TEST_CASE("a stiff, nearly undamped column closes on the event path: the Newton step and the periodic test follow the map's scales") {
  const auto net = test::network_from(kStiffColumn, "col");
  for (double u0 : {0.03, 1.0}) {
    const auto point = runtime::try_closed_form_harmonic_point(net, u0, 0.8596, HarmonicDefinition::thesis);
    CAPTURE(u0);
    REQUIRE(point.has_value());
    CHECK(point->cycles <= 12);
    check_against_time_stepping(net, u0, 0.8596, 1, 1e-5);
  }
}

namespace {

// The piecewise-linear subtree of NET (the first one) as a branch.
runtime::PwlBranch branch_of(const runtime::Network& net) {
  runtime::PwlBranch branch;
  for (int root : net.topology().subtrees)
    if (runtime::PwlBranch::build(net, root, branch)) return branch;
  FAIL("no piecewise-linear subtree");
  return branch;
}

const char* kOddBranches[] = {
    "model a { series f { slider cap (fy = 60 N)\n spring k1 (k = 600 N/mm)\n parallel y { inerter column (b = 40 kg)\n"
    " dashpot channel (c = 3.0 N*s/mm)\n spring bulge (k = 150 N/mm) } } }",
    "model a { series arm { slider s (fy = 45 N)\n maxwell m (k = 300 N/mm, tau = 20 ms) } }",
    "model a { series s { friction f1 (k = 400 N/mm, uy = 0.1 mm)\n"
    " parallel p { friction f2 (k = 100 N/mm, uy = 0.2 mm)\n maxwell m (k = 80 N/mm, tau = 5 ms) } } }",
    "model a { series s { gap g (width = 0.2 mm)\n slider s (fy = 20 N)\n spring k (k = 300 N/mm) } }"};

// CHECK_POINT(half, full, u0, omega) for every odd branch above as it is (the half-period map)
// and with its oddness switched off (the full one), at 0.05, 0.5 and 2 mm and 0.5, 7 and 40 Hz.
template <class Check>
void for_each_odd_point(Check check_point) {
  for (const char* model : kOddBranches) {
    const auto net = test::network_from(model, "a");
    runtime::PwlBranch half = branch_of(net), full = half;
    REQUIRE(half.odd);
    full.odd = false;
    for (double u0 : {0.05, 0.5, 2.0})
      for (double f : {0.5, 7.0, 40.0}) {
        const std::string text = model;
        CAPTURE(text);
        CAPTURE(u0);
        CAPTURE(f);
        check_point(half, full, u0, 2.0 * std::numbers::pi * f);
      }
  }
}

// CHECK_STATE(state) for the periodic state of every odd branch above, on the half-period map
// and on the full one, at the points of for_each_odd_point.
template <class Check>
void for_each_odd_state(Check check_state) {
  for_each_odd_point([&](const runtime::PwlBranch& half, const runtime::PwlBranch& full, double u0, double omega) {
    for (const runtime::PwlBranch* branch : {&half, &full}) {
      runtime::PwlPeriodicState s;
      REQUIRE(s.solve(*branch, u0, omega));
      check_state(s);
    }
  });
}

}  // namespace

TEST_CASE("the half-period map of an odd branch closes on the full-period map's periodic state") {
  // Two paths to one state: X0 -> -X(T/2) (what odd branches use) and X0 -> X(T) with the
  // half-wave symmetry checked afterwards (what a branch with an uneven law uses).
  for_each_odd_point([](const runtime::PwlBranch& half, const runtime::PwlBranch& full, double u0, double omega) {
    runtime::PwlPeriodicState a, b;
    REQUIRE(a.solve(half, u0, omega));
    REQUIRE(b.solve(full, u0, omega));
    const double scale = std::hypot(b.storage(), b.loss()) + 1e-12;  // 0 where a gap never closes
    CHECK(std::abs(a.storage() - b.storage()) < 1e-9 * scale);
    CHECK(std::abs(a.loss() - b.loss()) < 1e-9 * scale);
    double largest = 0.0, difference = 0.0;
    for (int k = 0; k < 32; ++k) {
      const double theta = (k + 0.3) * std::numbers::pi / 16.0;
      largest = std::max(largest, std::abs(b.force(theta)));
      difference = std::max(difference, std::abs(a.force(theta) - b.force(theta)));
    }
    CHECK(difference <= 1e-9 * largest + 1e-12);
    CHECK(a.switch_phases().size() == b.switch_phases().size());
  });
}

TEST_CASE("modes built once serve every point of a branch, and other parameters rebuild them") {
  const auto first = test::network_from(kOddBranches[0], "a");
  const auto second = test::network_from(std::string(kOddBranches[0]).replace(std::string(kOddBranches[0]).find("60 N"), 4, "25 N"), "a");
  const runtime::PwlBranch one = branch_of(first), other = branch_of(second);
  const double omega = 2.0 * std::numbers::pi * 11.0;
  runtime::PwlPeriodicState reused;
  REQUIRE(reused.solve(one, 2.0, 2.0 * std::numbers::pi * 3.0));  // builds the modes at another drive
  auto same = [&](const runtime::PwlBranch& branch) {
    runtime::PwlPeriodicState fresh;
    REQUIRE(reused.solve(branch, 0.7, omega));
    REQUIRE(fresh.solve(branch, 0.7, omega));
    CHECK(reused.storage() == doctest::Approx(fresh.storage()).epsilon(1e-13));
    CHECK(reused.loss() == doctest::Approx(fresh.loss()).epsilon(1e-13));
    return fresh.loss();
  };
  const double loss_one = same(one), loss_other = same(other);
  CHECK(std::abs(loss_one - loss_other) > 1e-3 * std::abs(loss_one));  // the cap slips at 25 N, not at 60 N
}

TEST_CASE("slopes carried from sample to sample equal the slope at each phase, across pieces and the half period") {
  // PwlPeriodicState::slopes against derivatives() (a modal exponential per phase) at every
  // sample, for odd branches on the half-period map and the same on the full one, over runs
  // that cross switches, the half period and the period.
  for_each_odd_state([](const runtime::PwlPeriodicState& s) {
    // On the half cycle's grid (the grid step's propagator), off it, and with an offset.
    for (const auto& [from, step, count, offset] :
         {std::tuple{-0.5 * std::numbers::pi, std::numbers::pi / 32.0, 32, 0.0}, std::tuple{0.1, 0.37, 40, 0.0}, std::tuple{-7.0, 0.05, 30, 0.0},
          std::tuple{-0.5 * std::numbers::pi, std::numbers::pi / 32.0, 40, std::numbers::pi}}) {
      std::vector<double> first(static_cast<std::size_t>(count) + 1), phases;
      for (int j = 0; j <= count; ++j) phases.push_back(from + j * step);
      s.slopes(phases.data(), count + 1, offset, first.data());
      double largest = 0.0, difference = 0.0;
      for (int j = 0; j <= count; ++j) {
        double expected = 0.0, second = 0.0;
        s.derivatives(from + j * step + offset, expected, second);
        largest = std::max(largest, std::abs(expected));
        difference = std::max(difference, std::abs(expected - first[static_cast<std::size_t>(j)]));
      }
      CHECK(difference <= 1e-10 * largest + 1e-13);
    }
  });
}

TEST_CASE("the slopes recorded on the grid as the steady cycle passed equal the slope at each grid phase") {
  // PwlPeriodicState::grid_slope (recorded by the shooting's last cycle) against derivatives()
  // (a modal exponential from the piece's start) at theta = 2 pi k/64 over three periods, on
  // the half-period map (the mirrored half by -F(theta - pi)) and on the full one; a grid
  // point on a switch (a kink: the slope after it is recorded) is skipped.
  for_each_odd_state([](const runtime::PwlPeriodicState& s) {
    double largest = 0.0, difference = 0.0;
    int compared = 0;
    for (int k = -64; k < 128; ++k) {
      const double theta = 2.0 * std::numbers::pi * k / 64.0;
      const double cycle_phase = std::fmod(std::fmod(theta, 2.0 * std::numbers::pi) + 2.0 * std::numbers::pi, 2.0 * std::numbers::pi);
      const auto& kinks = s.switch_phases();
      if (std::any_of(kinks.begin(), kinks.end(), [&](double kink) {
            const double d = std::abs(kink - cycle_phase);
            return std::min(d, 2.0 * std::numbers::pi - d) < 1e-6;
          }))
        continue;
      double expected = 0.0, second = 0.0;
      s.derivatives(theta, expected, second);
      largest = std::max(largest, std::abs(expected));
      difference = std::max(difference, std::abs(expected - s.grid_slope(k)));
      ++compared;
    }
    CHECK(compared > 150);
    CHECK(difference <= 1e-10 * largest + 1e-13);
  });
}

TEST_CASE("a solve of the same branch at a drive solved before restores that result to the last bit") {
  // Solving at other drives in between, and a branch with other values (which drops what was
  // kept), must not change what a repeated drive returns: the same storage, loss, cycles,
  // switch phases and force as a state that never solved anything else.
  const auto net = test::network_from(kOddBranches[0], "a");
  const auto other_net = test::network_from(std::string(kOddBranches[0]).replace(std::string(kOddBranches[0]).find("60 N"), 4, "25 N"), "a");
  const runtime::PwlBranch branch = branch_of(net), other = branch_of(other_net);
  const double drives[][2] = {{0.05, 3.0}, {0.5, 11.0}, {2.0, 40.0}, {0.5, 3.0}};
  runtime::PwlPeriodicState kept;
  for (int round = 0; round < 3; ++round) {
    if (round == 2) REQUIRE(kept.solve(other, 0.5, 2.0 * std::numbers::pi * 11.0));
    for (const auto& d : drives) {
      CAPTURE(round);
      CAPTURE(d[0]);
      CAPTURE(d[1]);
      const double omega = 2.0 * std::numbers::pi * d[1];
      runtime::PwlPeriodicState fresh;
      REQUIRE(fresh.solve(branch, d[0], omega));
      REQUIRE(kept.solve(branch, d[0], omega));
      CHECK(kept.storage() == fresh.storage());
      CHECK(kept.loss() == fresh.loss());
      CHECK(kept.cycles() == fresh.cycles());
      CHECK(kept.switch_phases() == fresh.switch_phases());
      for (int k = 0; k < 16; ++k) {
        const double theta = (k + 0.3) * std::numbers::pi / 8.0;
        CHECK(kept.force(theta) == fresh.force(theta));
      }
    }
  }
  // The other branch's values give another result at the same drive (nothing stale is restored).
  runtime::PwlPeriodicState fresh_other;
  REQUIRE(fresh_other.solve(other, 0.5, 2.0 * std::numbers::pi * 11.0));
  REQUIRE(kept.solve(other, 0.5, 2.0 * std::numbers::pi * 11.0));
  CHECK(kept.loss() == fresh_other.loss());
  REQUIRE(kept.solve(branch, 0.5, 2.0 * std::numbers::pi * 11.0));
  CHECK(std::abs(kept.loss() - fresh_other.loss()) > 1e-3 * std::abs(kept.loss()));
}

// A warm solve from a recorded start (pwl_warm_start.hpp) on a state that kept nothing gives the
// bits of the solve that recorded it: its first cycle is the recorded closing cycle, tested as
// that one was. Where the closing cycle passed the per-coordinate periodic test (PwlStart::
// allowed) and the warm solve's first cycle met the plain test alone, it took a Newton step
// instead, and a Jacobian column's point gave other bits on a thread that had not kept the base
// solve than on one that had: `rheo diagnose --threads 2` printed other digits in about one run
// of five on a loaded machine.
TEST_CASE("a warm solve from a recorded start gives the recording solve's bits, also where that closed by the per-coordinate test") {
  // The stiff column above (its velocity answers its position by omega_n / omega ~ 1.5e6).
  const auto net = test::network_from(kStiffColumn, "col");
  const runtime::PwlBranch branch = branch_of(net);
  int relaxed = 0;
  for (const double u0 : {0.03, 0.3, 1.0})
    for (const double f : {0.8596, 3.0}) {
      CAPTURE(u0);
      CAPTURE(f);
      const double omega = 2.0 * std::numbers::pi * f;
      runtime::PwlPeriodicState cold, warm;
      REQUIRE(cold.solve(branch, u0, omega));
      const runtime::PwlStart recorded = cold.start();
      relaxed += recorded.allowed.size() > 0 ? 1 : 0;
      REQUIRE(warm.solve(branch, u0, omega, &recorded));
      CHECK(warm.cycles() == 1);
      CHECK(warm.storage() == cold.storage());
      CHECK(warm.loss() == cold.loss());
      CHECK(warm.switch_phases() == cold.switch_phases());
    }
  CHECK(relaxed > 0);  // the case the allowance carries
}

TEST_CASE("a branch with other values refills the storage of the last branch's modes: the same bits as a fresh state") {
  // The column's mass changes the modes' state block (its eigendecomposition, kept per mode):
  // a state that solved the first branch, then the second, then the first again gives each
  // the bits of a state that never solved another.
  const std::string text = kOddBranches[0];
  const auto heavy_net = test::network_from(std::string(text).replace(text.find("40 kg"), 5, "55 kg"), "a");
  const runtime::PwlBranch light = branch_of(test::network_from(text, "a")), heavy = branch_of(heavy_net);
  runtime::PwlPeriodicState kept;
  for (const runtime::PwlBranch* branch : {&light, &heavy, &light}) {
    for (const auto& point : {std::pair{0.5, 11.0}, std::pair{2.0, 40.0}}) {
      const double u0 = point.first, f = point.second;  // not a structured binding: Clang 14 cannot capture one
      CAPTURE(u0);
      CAPTURE(f);
      const double omega = 2.0 * std::numbers::pi * f;
      runtime::PwlPeriodicState fresh;
      REQUIRE(fresh.solve(*branch, u0, omega));
      REQUIRE(kept.solve(*branch, u0, omega));
      CHECK(kept.storage() == fresh.storage());
      CHECK(kept.loss() == fresh.loss());
      CHECK(kept.cycles() == fresh.cycles());
    }
  }
}

}  // namespace pwl_periodic_test
