// The drive stepper against hand solutions: a spring k u_j, a dashpot c (u_j - u_j-1)/(t_j -
// t_j-1) on irregular steps (a new plan at each change of step), a Maxwell arm's exact
// exponential update, and element outputs from a relaxed start away from rest.
#include "runtime/stepping/drive_stepper.hpp"

#include "support.hpp"

#include <doctest/doctest.h>

#include <cmath>

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

}  // namespace drive_stepper_test
