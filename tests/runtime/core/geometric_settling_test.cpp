// Settling by cycles accelerated where it is geometric (runtime/core/geometric_settling.hpp):
// which rate pairs count as a steady contraction, and the component-wise skip against hand
// sequences: each component to its own limit, none moved on another's rate, none on noise.
#include "runtime/core/geometric_settling.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <vector>

namespace geometric_settling_test {

using rheo::runtime::ComponentSettling;
using rheo::runtime::steady_contraction;

TEST_CASE("steady contraction: rates from 0.3 to 1 that agree within 5 % of the smaller of rho and 1 - rho") {
  CHECK(steady_contraction(0.5, 0.51));
  CHECK_FALSE(steady_contraction(0.5, 0.53));
  CHECK(steady_contraction(0.9993, 0.99931));         // reproducer 03's slow set
  CHECK_FALSE(steady_contraction(0.99887, 1.00023));  // 880 times a change known to 100 % (was taken)
  CHECK_FALSE(steady_contraction(0.98, 0.97));        // 1 - rho = 0.02: a spread of 0.01 is half of it
  CHECK(steady_contraction(0.98, 0.9795));
  CHECK_FALSE(steady_contraction(0.2, 0.2));  // fast: a few cycles finish anyway
  CHECK_FALSE(steady_contraction(1.0, 1.0));
}

TEST_CASE("component settling: each geometric component jumps to its own limit, the others keep their values") {
  // Component 0 settles to 2 at rate 0.9, component 1 to -1 at rate 0.5 (scale 10), component 2
  // swings without settling (an undamped mass), component 3 is settled but for noise below the floor.
  ComponentSettling settling({1.0, 10.0, 1.0, 1.0}, 1e-6);
  std::vector<double> target;
  const auto state = [](int n) {
    return std::vector<double>{2.0 - std::pow(0.9, n), -1.0 + 3.0 * std::pow(0.5, n), std::sin(1.3 * n), 5.0 + 1e-8 * ((n * 7) % 3)};
  };
  for (int n = 0; n < 3; ++n) CHECK_FALSE(settling.record(state(n), target));  // four records make three changes
  REQUIRE(settling.record(state(3), target));
  CHECK(target[0] == doctest::Approx(2.0).epsilon(1e-12));
  CHECK(target[1] == doctest::Approx(-1.0).epsilon(1e-12));
  CHECK(target[2] == state(3)[2]);
  CHECK(target[3] == state(3)[3]);
  // After forget() the next three records only gather changes again.
  settling.forget();
  for (int n = 4; n < 7; ++n) CHECK_FALSE(settling.record(state(n), target));
  CHECK(settling.record(state(7), target));
}

TEST_CASE("component settling: a change that flips sign, speeds up or slows down is not extrapolated") {
  ComponentSettling settling({1.0, 1.0, 1.0}, 1e-6);
  std::vector<double> target;
  // 0: alternating about a limit (rate -0.8); 1: rates 0.5 then 0.9; 2: a steady drift (rate 1).
  const std::vector<std::vector<double>> states = {{0.0, 0.0, 0.0}, {1.0, 1.0, 1.0}, {0.2, 1.5, 2.0}, {0.84, 1.95, 3.0}};
  for (const auto& s : states) CHECK_FALSE(settling.record(s, target));
}

TEST_CASE("component settling: a skip the integrator could not take is not tried again for its components, others still skip") {
  // Component 0 contracts at 0.9 from the start; component 1 holds still, then contracts at 0.5.
  ComponentSettling settling({1.0, 1.0}, 1e-9);
  std::vector<double> target;
  const auto state = [](int n) { return std::vector<double>{2.0 - std::pow(0.9, n), n < 4 ? 1.0 : 2.0 - std::pow(0.5, n - 3)}; };
  for (int n = 0; n < 4; ++n) CHECK(settling.record(state(n), target) == (n == 3));
  CHECK_FALSE(settling.refused());
  settling.refuse_last();  // the integrator found no state at component 0's limit
  CHECK(settling.refused());
  for (int n = 4; n < 6; ++n) CHECK_FALSE(settling.record(state(n), target));
  REQUIRE(settling.record(state(6), target));
  CHECK(target[0] == state(6)[0]);
  CHECK(target[1] == doctest::Approx(2.0).epsilon(1e-12));
}

TEST_CASE("component settling: a slow mode whose changes fell below the floor still jumps while its distance left is above it") {
  // Component 0 contracts at 0.994 with changes of about 6e-8, below the floor of 1e-6 but 1e-5
  // from its limit (differential seed 2026, model 0, on IDA); component 1 at the same rate with
  // changes below the noise of 1e-8; component 2 at 0.5, its change at the fourth record 2.5e-8,
  // as far from its limit.
  ComponentSettling settling({1.0, 1.0, 1.0}, 1e-6, 1e-8);
  std::vector<double> target;
  const auto state = [](int n) {
    return std::vector<double>{1.0 - 1e-5 * std::pow(0.994, n), 3.0 - 1e-7 * std::pow(0.994, n), 2.0 - 4e-7 * std::pow(0.5, n)};
  };
  for (int n = 0; n < 3; ++n) CHECK_FALSE(settling.record(state(n), target));
  REQUIRE(settling.record(state(3), target));
  CHECK(target[0] == doctest::Approx(1.0).epsilon(1e-10));  // a move of 1e-5 from changes known to 2e-9
  CHECK(target[1] == state(3)[1]);
  CHECK(target[2] == state(3)[2]);
  // With the noise at the floor (the default), as before: none moves.
  ComponentSettling floor_only({1.0, 1.0, 1.0}, 1e-6);
  for (int n = 0; n < 4; ++n) CHECK_FALSE(floor_only.record(state(n), target));
}

}  // namespace geometric_settling_test
