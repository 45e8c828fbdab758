// The drive stepper against hand solutions: a spring k u_j, a dashpot c (u_j - u_j-1)/(t_j -
// t_j-1) on irregular steps (a new plan at each change of step), a Maxwell arm's exact
// exponential update, and element outputs from a relaxed start away from rest. Its error
// control against the closed form of a standard linear solid whose time is a tenth of the step.
#include "runtime/stepping/drive_stepper.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace drive_stepper_test {

using namespace rheo;

TEST_CASE("spring, dashpot and Maxwell arm stepped sample by sample match their hand solutions") {
  const runtime::Network network = test::network_from(
      "model m { spring s (k = 20 N/mm)\n dashpot c (c = 3 N*s/mm)\n maxwell a (k = 50 N/mm, tau = 0.1 s) }", "m");
  runtime::DriveStepper stepper(network, true);
  const double times[] = {0.0, 0.01, 0.03, 0.04, 0.1, 0.15};
  const double disps[] = {0.0, 0.2, 0.1, 0.4, 0.4, -0.3};
  double maxwell = 0.0;
  CHECK(stepper.start(times[0], disps[0]) == 0.0);
  for (int j = 1; j < 6; ++j) {
    const double dt = times[j] - times[j - 1], rate = (disps[j] - disps[j - 1]) / dt;
    // Maxwell under a constant rate over the step: F <- F e^{-dt/tau} + k tau rate (1 - e^{-dt/tau}).
    maxwell = maxwell * std::exp(-dt / 0.1) + 50.0 * 0.1 * rate * (1.0 - std::exp(-dt / 0.1));
    const double force = stepper.step(times[j], disps[j]);
    CHECK(force == doctest::Approx(20.0 * disps[j] + 3.0 * rate + maxwell).epsilon(1e-12));
    CHECK(stepper.element_force()[0] == doctest::Approx(20.0 * disps[j]).epsilon(1e-14));
    CHECK(stepper.element_force()[1] == doctest::Approx(3.0 * rate).epsilon(1e-12));
    CHECK(stepper.element_force()[2] == doctest::Approx(maxwell).epsilon(1e-12));
  }
}

TEST_CASE("a relaxed start away from rest: the springs carry their force, the rest none, elongations at u0") {
  const runtime::Network network = test::network_from("model m { spring s (k = 20 N/mm)\n maxwell a (k = 50 N/mm, tau = 0.1 s) }", "m");
  runtime::DriveStepper stepper(network, true);
  CHECK(stepper.start(0.0, 0.5) == doctest::Approx(10.0));
  CHECK(stepper.element_force()[0] == doctest::Approx(10.0));
  CHECK(stepper.element_force()[1] == 0.0);
  CHECK(stepper.element_elongation()[0] == doctest::Approx(0.5).scale(0.0));
  // Held: nothing changes.
  CHECK(stepper.step(1.0, 0.5) == doctest::Approx(10.0));
  CHECK_THROWS_AS(stepper.step(1.0, 0.6), std::logic_error);  // time must increase
}

// A spring k1 in series with a spring k2 beside a dashpot c, from rest, driven at rate v to U
// over [0, t1] and held: the dashpot's elongation x obeys c x' = k1 (u - x) - k2 x, so with
// tau = c/(k1 + k2) and a = k1 v/(k1 + k2)
//   x = a (t - tau (1 - e^{-t/tau}))                         on the ramp,
//   x = x_inf + (x(t1) - x_inf) e^{-(t - t1)/tau}            held, x_inf = k1 U/(k1 + k2),
// and F = k1 (u - x).
TEST_CASE("error control: a stiff internal node follows its closed form where one step a sample does not") {
  const double k1 = 200.0, k2 = 50.0, c = 0.025;  // N/mm, N*s/mm: tau = 0.1 ms
  const runtime::Network network = test::network_from(
      "model m { series { spring a (k = 200 N/mm)\n parallel { spring b (k = 50 N/mm)\n dashpot d (c = 0.025 N*s/mm) } } }", "m");
  const double tau = c / (k1 + k2), v = 100.0, t1 = 5e-3, dt = 1e-3;  // mm/s, s
  const double u_top = v * t1, a = k1 * v / (k1 + k2), x1 = a * (t1 - tau * (1.0 - std::exp(-t1 / tau)));
  const auto exact = [&](double t) {
    const double x = t <= t1 ? a * (t - tau * (1.0 - std::exp(-t / tau)))
                             : k1 * u_top / (k1 + k2) + (x1 - k1 * u_top / (k1 + k2)) * std::exp(-(t - t1) / tau);
    return k1 * (std::min(v * t, u_top) - x);
  };
  const auto worst_error = [&](double tolerance, long* steps) {
    runtime::DriveStepper stepper(network, true, tolerance);
    stepper.start(0.0, 0.0);
    double worst = 0.0, peak = 0.0;
    for (int j = 1; j <= 10; ++j) {
      const double t = j * dt, force = stepper.step(t, std::min(v * t, u_top));
      CHECK(stepper.element_force()[0] == doctest::Approx(force).epsilon(1e-12));  // the chain's spring carries it all
      worst = std::max(worst, std::abs(force - exact(t)));
      peak = std::max(peak, std::abs(exact(t)));
    }
    *steps = stepper.steps();
    return worst / peak;
  };
  long one = 0, controlled = 0;
  const double uncontrolled_error = worst_error(0.0, &one);
  const double controlled_error = worst_error(runtime::DriveStepper::kDefaultTolerance, &controlled);
  CHECK(one == 10);
  CHECK(uncontrolled_error > 5e-3);  // first order with dt = 10 tau: 0.67 % of the largest force at the kinks
  CHECK(controlled_error < 3e-5);    // 5.7e-6: the halves extrapolated, their difference held to 1e-3
  CHECK(controlled > 10 * one);
  CHECK(controlled < 3 * 10 * (1 << runtime::DriveStepper::kMaxHalvings));
}

// NETWORK on 300 samples (1 ms) of a two-sine drive, controlled and one step a sample, against
// the same drive cut into 512 linear pieces a sample, one step each (64 or 2048 pieces change
// that reference by less than 2e-5 of its peak). Their largest errors relative to its peak.
struct AgainstFineSteps {
  double controlled = 0.0, one = 0.0;
  long steps = 0;
};
AgainstFineSteps against_fine_steps(const runtime::Network& network) {
  const auto drive = [](double t) { return 0.3 * std::sin(2 * std::numbers::pi * 3.0 * t) + 0.05 * std::sin(2 * std::numbers::pi * 41.0 * t); };
  constexpr int samples = 300, fine = 512;
  runtime::DriveStepper controlled(network, false), one(network, false, 0.0), reference(network, false, 0.0);
  controlled.start(0.0, 0.0);
  one.start(0.0, 0.0);
  reference.start(0.0, 0.0);
  double peak = 0.0;
  AgainstFineSteps r;
  for (int j = 1; j <= samples; ++j) {
    const double t0 = 1e-3 * (j - 1), t1 = 1e-3 * j;
    double exact = 0.0;
    for (int i = 1; i <= fine; ++i) {
      const double w = static_cast<double>(i) / fine;
      exact = reference.step(t0 + w * (t1 - t0), drive(t0) + w * (drive(t1) - drive(t0)));
    }
    peak = std::max(peak, std::abs(exact));
    r.controlled = std::max(r.controlled, std::abs(controlled.step(t1, drive(t1)) - exact));
    r.one = std::max(r.one, std::abs(one.step(t1, drive(t1)) - exact));
  }
  r.controlled /= peak;
  r.one /= peak;
  r.steps = controlled.steps();
  return r;
}

// A chain that is not linear (a friction element in it: its halves are kept, not extrapolated).
TEST_CASE("error control: a friction element in series with a stiff Kelvin-Voigt pair agrees with fine steps") {
  const AgainstFineSteps r = against_fine_steps(
      test::network_from("model m { spring s (k = 30 N/mm)\n series { friction f (k = 200 N/mm, fy = 4 N)\n parallel { spring b (k = 50 N/mm)\n"
                         " dashpot d (c = 0.05 N*s/mm) } } }",
                         "m"));
  CHECK(r.one > 3e-3);         // 0.65 %
  CHECK(r.controlled < 1e-3);  // 2.9e-4: halves kept where their difference is within a tenth of the tolerance
  CHECK(r.steps > 3 * 300);
}

// Where a gap shuts follows from the elongations its chain kept when it last opened: the gap's
// elongation is compared as well, as a force through the chain's springs.
TEST_CASE("error control: a dashpot, a gap and a spring in series agree with fine steps where the gap shuts") {
  const AgainstFineSteps r = against_fine_steps(test::network_from(
      "model m { series { dashpot d (c = 0.32 N*s/mm)\n gap g (width = 0.18 mm, center = -0.058 mm)\n spring s (k = 137 N/mm) } }", "m"));
  CHECK(r.one > 1e-2);         // 2.0 %
  CHECK(r.controlled < 1e-3);  // 1.4e-4 (2.4e-3 with the gap's elongation left out of the comparison)
}

// Exact: a slider-capped Maxwell arm, a rate-independent chain, the root block alone. Left to
// Newmark's second-order step: a fluid column (a subtree with an inerter).
TEST_CASE("error control leaves exact subtrees and inerters at one step a sample") {
  for (const char* source : {"model m { spring s (k = 20 N/mm)\n series { slider p (fy = 5 N)\n maxwell a (k = 50 N/mm, tau = 0.1 ms) } }",
                             "model m { series { spring s (k = 20 N/mm)\n friction f (k = 40 N/mm, fy = 3 N)\n gap g (width = 0.1 mm) } }",
                             "model m { spring s (k = 20 N/mm)\n dashpot d (c = 1 N*s/mm)\n maxwell a (k = 50 N/mm, tau = 0.1 ms) }",
                             "model m { series { spring s (k = 300 N/mm)\n parallel { inerter b (b = 1.4 kg)\n dashpot d (c = 0.1 N*s/mm) } } }"}) {
    CAPTURE(source);
    const runtime::Network network = test::network_from(source, "m");
    runtime::DriveStepper stepper(network, false);
    stepper.start(0.0, 0.0);
    for (int j = 1; j <= 20; ++j) stepper.step(1e-3 * j, 0.3 * std::sin(0.7 * j));
    CHECK(stepper.steps() == 20);
  }
}

}  // namespace drive_stepper_test
