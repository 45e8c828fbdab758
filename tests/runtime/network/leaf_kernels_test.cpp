// Leaf laws by hand: the one-sided return mapping, the polynomial spring and its monotone range,
// a gap's centre as the kernels take it.
#include "runtime/network/leaf_kernels.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace leaf_kernels_test {

using namespace rheo::runtime;

TEST_CASE("one-sided return mapping: the trial force clamped to [-fy_neg, fy_pos]") {
  CHECK(friction_step(2.0, 3.0, 5.0, 0.0, 1.0).force == 2.0);
  CHECK(friction_step(2.0, 3.0, 5.0, 0.0, 1.0).slope == 2.0);
  CHECK(friction_step(2.0, 3.0, 5.0, 0.0, 2.0).force == 3.0);
  CHECK(friction_step(2.0, 3.0, 5.0, 0.0, 2.0).slope == 0.0);
  CHECK(friction_step(2.0, 3.0, 5.0, 0.0, -2.0).force == -4.0);
  CHECK(friction_step(2.0, 3.0, 5.0, 0.0, -3.0).force == -5.0);
  // Equal sides are the symmetric element.
  for (double de : {-4.0, -1.0, 0.5, 3.0}) CHECK(friction_step(2.0, 3.0, 3.0, 1.0, de).force == friction_step(2.0, 3.0, 1.0, de).force);
}

TEST_CASE("poly_spring: F = k1 e + k2 e^2 + k3 e^3 and its tangent, the tangent's zeros bound the monotone range") {
  const PolyLaw law{10.0, -1.0, 0.2};
  CHECK(law.force(2.0) == doctest::Approx(10.0 * 2 - 4.0 + 0.2 * 8));
  CHECK(law.force(-2.0) == doctest::Approx(-20.0 - 4.0 - 1.6));
  CHECK(law.slope(-2.0) == doctest::Approx(10.0 + 4.0 + 2.4));
  CHECK(std::isinf(law.monotone_range().lo));  // k2^2 = 1 < 3 k1 k3 = 6: monotone everywhere
  CHECK(std::isinf(law.monotone_range().hi));
  // k3 = 0: the tangent 10 + 2 k2 e vanishes at e = -10/(2 k2) on one side only.
  const PolyLaw quadratic{10.0, 2.0, 0.0};
  CHECK(quadratic.monotone_range().lo == doctest::Approx(-2.5));
  CHECK(std::isinf(quadratic.monotone_range().hi));
  // k3 < 0: zeros on both sides, the roots of -3 e^2 + 4 e + 10.
  const PolyLaw soft{10.0, 2.0, -1.0};
  const double disc = std::sqrt(16.0 + 120.0);
  CHECK(soft.monotone_range().lo == doctest::Approx((4.0 - disc) / 6.0));
  CHECK(soft.monotone_range().hi == doctest::Approx((4.0 + disc) / 6.0));
  CHECK(soft.slope(soft.monotone_range().hi) == doctest::Approx(0.0).scale(10.0));
}

TEST_CASE("a gap's centre is taken within +-width/2") {
  CHECK(gap_center(1.0, 0.3) == 0.3);
  CHECK(gap_center(1.0, 0.7) == 0.5);
  CHECK(gap_center(1.0, -0.7) == -0.5);
}

}  // namespace leaf_kernels_test
