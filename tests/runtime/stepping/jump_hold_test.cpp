// The ramp-and-hold step in one pass against its definition, the two kernel steps (a ramp over
// delta, then a hold), on held staircases that take capped chains through every mode, and which
// networks it applies to.
#include "runtime/stepping/jump_hold.hpp"

#include "runtime/stepping/relaxed_state.hpp"
#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <stdexcept>
#include <string>

namespace jump_hold_test {

using namespace rheo;

namespace {

struct Comparison {
  double peak = 0.0;         // largest |F| [N] of the two-step path
  double worst_force = 0.0;  // largest |F| difference [N] of the one-pass path from it
  double noise_force = 0.0;  // ... of the two-step path on the input scaled by 1 + 2^-52
  bool states_agree = true;  // every slot within 4 times its noise, or 1e-12 of its largest magnitude
  // Steps whose ramp (0), whose hold (1) ends with the chain's force at its upper cap, its lower
  // cap, strictly inside.
  std::array<int, 2> upper{}, lower{}, interior{};
};

// The staircase u_n = AMPLITUDE (sin(2 pi 3 t) + 0.25 sin(2 pi 17 t)) + 0.2 t, t = n h, held over
// each step of h = 2^-11 s (the fmusim conformance test's), from the relaxed state at u_0: the
// one-pass step against the two kernel steps over 2000 steps, and the two kernel steps against
// themselves on the input scaled by 1 + 2^-52 (what rounding alone moves them by: the ramp's
// step behind an inerter, of slope 4 b / delta^2, amplifies it). CHAIN_SLOT: the state slot of
// a capped chain's force to classify by CAP = {lower, upper} (-1: none).
Comparison compare(const runtime::Network& net, double amplitude, int chain_slot = -1, std::pair<double, double> cap = {0.0, 0.0}) {
  const double h = 1.0 / 2048.0, delta = h / 1024.0;
  const runtime::Simulator sim(net);
  const auto ramp = runtime::StepPlan::make(net, delta), hold = runtime::StepPlan::make(net, h - delta);
  const runtime::JumpHoldStep one(net, h, delta);
  CHECK(one.dt() == h);
  auto u = [&](int n, double scale) {
    const double t = n * h;
    return scale * amplitude * (std::sin(2 * std::numbers::pi * 3.0 * t) + 0.25 * std::sin(2 * std::numbers::pi * 17.0 * t)) + 0.2 * t;
  };
  Comparison c;
  runtime::State mid, after;
  auto two_steps = [&](runtime::State& s, double to) {
    mid = after = s;
    sim.step(ramp, s, to, mid);
    sim.step(hold, mid, to, after);
    std::swap(s, after);
  };
  auto classify = [&](const runtime::State& s, int part) {
    const double chain = s.values[static_cast<std::size_t>(chain_slot)];
    (chain >= cap.second ? c.upper : chain <= cap.first ? c.lower : c.interior)[static_cast<std::size_t>(part)] += 1;
  };
  runtime::State two = runtime::relaxed_state(net, u(0, 1.0)), nudged = two, single = two, next = two;
  const std::size_t slots = two.values.size();
  std::vector<double> scale(slots, 0.0), worst(slots, 0.0), noise(slots, 0.0);
  for (int n = 1; n <= 2000; ++n) {
    two_steps(nudged, u(n, 1.0 + 0x1p-52));
    two_steps(two, u(n, 1.0));
    if (chain_slot >= 0) classify(mid, 0), classify(two, 1);
    const double f = one.step(sim, single, u(n, 1.0), next);
    CHECK(f == next.force);
    CHECK(next.u == u(n, 1.0));
    std::swap(single, next);
    c.peak = std::max(c.peak, std::abs(two.force));
    c.worst_force = std::max(c.worst_force, std::abs(single.force - two.force));
    c.noise_force = std::max(c.noise_force, std::abs(nudged.force - two.force));
    for (std::size_t i = 0; i < slots; ++i) {
      scale[i] = std::max(scale[i], std::abs(two.values[i]));
      worst[i] = std::max(worst[i], std::abs(single.values[i] - two.values[i]));
      noise[i] = std::max(noise[i], std::abs(nudged.values[i] - two.values[i]));
    }
  }
  for (std::size_t i = 0; i < slots; ++i) c.states_agree &= worst[i] <= 4.0 * noise[i] + 1e-12 * scale[i];
  return c;
}

void check_agrees(const Comparison& c) {
  CHECK(c.peak > 1.0);
  CHECK(c.worst_force <= 4.0 * c.noise_force + 1e-13 * c.peak);
  CHECK(c.states_agree);
}

// The first PARTS parts of the step met the chain free and slipping both ways, many times.
void check_modes(const Comparison& c, std::size_t parts) {
  for (std::size_t part = 0; part < parts; ++part) {
    CAPTURE(part);
    CHECK(c.upper[part] > 50);
    CHECK(c.lower[part] > 50);
    CHECK(c.interior[part] > 50);
  }
}

int node_state(const runtime::Network& net, const std::string& path) {
  for (const auto& probe : net.topology().probes)
    if (probe.path == path) return net.topology().nodes[static_cast<std::size_t>(probe.index)].state;
  FAIL("no element " << path);
  return -1;
}

}  // namespace

TEST_CASE("jump_hold: the hydrobushing's ramp and hold in one pass is the two kernel steps, its fluid cap free and slipping both ways") {
  const auto net = test::network_from(test::read_file(std::string(RHEO_EXAMPLES_DIR) + "/hydrobushing.rheo"), "hydrobushing");
  REQUIRE(runtime::JumpHoldStep::applies(net.topology()));
  const int cap = node_state(net, "fluid.cap") + 1;
  const Comparison small = compare(net, 0.05, cap, {-60.0, 60.0});
  CHECK(small.interior == std::array<int, 2>{2000, 2000});
  check_agrees(small);
  const Comparison large = compare(net, 1.2, cap, {-60.0, 60.0});
  check_modes(large, 2);
  check_agrees(large);
  // Rounding, amplified behind the inerter: about 1e-9 of the peak force both ways.
  MESSAGE("hydrobushing: max |F| " << large.peak << " N; one pass against two steps " << large.worst_force << " N, two steps against "
                                   << "themselves on the input moved by an ulp " << large.noise_force << " N");
  CHECK(large.worst_force <= 1e-8 * large.peak);
}

TEST_CASE("jump_hold: root Maxwell, dashpot, friction and slider with a chain capped one-sidedly by a slider and a friction element") {
  const auto net = test::network_from(
      "model m {\n  spring k (k = 50 N/mm)\n  maxwell r (k = 80 N/mm, tau = 2 ms)\n  dashpot d (c = 0.5 N*s/mm)\n"
      "  friction rf (k = 300 N/mm, fy = 8 N)\n  slider rs (fy = 3 N)\n"
      "  series chain {\n    slider cap (fy_pos = 25 N, fy_neg = 10 N)\n    friction f (k = 400 N/mm, fy = 15 N)\n"
      "    maxwell m (k = 200 N/mm, tau = 50 ms)\n    spring s (k = 500 N/mm)\n  }\n}",
      "m");
  REQUIRE(runtime::JumpHoldStep::applies(net.topology()));
  // The chain's force lies in [-10, 15] N: the slider caps compression, the friction element tension.
  const int chain = net.topology().nodes[static_cast<std::size_t>(net.topology().subtrees.at(0))].state + 1;
  const Comparison c = compare(net, 1.0, chain, {-10.0, 15.0});
  check_modes(c, 1);  // the chain relaxes in every hold after it slipped
  check_agrees(c);
}

TEST_CASE("jump_hold: two linear subtrees, one with an inerter behind a spring") {
  const auto net = test::network_from(
      "model m {\n  series a {\n    spring k1 (k = 300 N/mm)\n    parallel y {\n      inerter i (b = 5 kg)\n      dashpot c (c = 0.8 N*s/mm)\n"
      "      spring k2 (k = 100 N/mm)\n    }\n  }\n  series b {\n    maxwell m (k = 120 N/mm, tau = 8 ms)\n    spring s (k = 400 N/mm)\n  }\n}",
      "m");
  REQUIRE(net.topology().subtrees.size() == 2);
  REQUIRE(runtime::JumpHoldStep::applies(net.topology()));
  check_agrees(compare(net, 0.5));
}

TEST_CASE("jump_hold: subtrees that are not piecewise affine are left to the two kernel steps") {
  for (const char* body : {"series { yeoh y (D10 = 1, D20 = 0.5, D30 = 0.1) spring s (k = 10) }",
                           "series { bouc_wen w (k = 100, n = 2, fy = 3) spring s (k = 10) }", "series { gap g (width = 0.2 mm) spring s (k = 10) }",
                           "series { spring a (k = 5) parallel { spring s (k = 1) series { slider c (fy = 1 N) spring s2 (k = 10) } } }",
                           "spring s (k = 10) inerter i (b = 1 kg)"}) {
    CAPTURE(std::string(body));
    const auto net = test::network_from(std::string("model m { ") + body + " }", "m");
    REQUIRE_FALSE(net.topology().subtrees.empty());
    CHECK_FALSE(runtime::JumpHoldStep::applies(net.topology()));
    CHECK_THROWS_AS(runtime::JumpHoldStep(net, 1e-3, 1e-6), std::logic_error);
  }
}

}  // namespace jump_hold_test
