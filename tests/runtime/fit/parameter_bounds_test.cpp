// runtime/fit/parameter_bounds.hpp: "at a bound" is measured in the search coordinate, ln p
// for positive bounds, as a fraction of the bounds' width.
#include "runtime/fit/parameter_bounds.hpp"

#include <doctest/doctest.h>

#include <cmath>

namespace parameter_bounds_test {

using namespace rheo;

namespace {
lang::Parameter bounded(double lower, double upper) {
  lang::Parameter p;
  p.free = true;
  p.lower = lower;
  p.upper = upper;
  return p;
}
}  // namespace

TEST_CASE("a value within 1e-4 of the bounds' width in ln p of a positive bound is at it") {
  const lang::Parameter tau = bounded(0.01, 10000.0);  // six decades
  CHECK(runtime::logarithmic_search(tau));
  CHECK(runtime::bound_reached(tau, 9999.93) == runtime::BoundSide::upper);  // 7e-6 in ln p
  CHECK(runtime::bound_reached(tau, 10000.0) == runtime::BoundSide::upper);
  CHECK(runtime::bound_reached(tau, 0.0100001) == runtime::BoundSide::lower);
  CHECK(runtime::bound_reached(tau, 9950.0) == runtime::BoundSide::none);  // 5e-3 in ln p, more than 1e-4 x 13.8
  CHECK(runtime::bound_reached(tau, 1.0) == runtime::BoundSide::none);
  CHECK(runtime::search_coordinate(tau, 1.0) == 0.0);
}

TEST_CASE("bounds reaching zero or below are searched in p, and measured so") {
  const lang::Parameter d20 = bounded(-10.0, 10.0);
  CHECK_FALSE(runtime::logarithmic_search(d20));
  CHECK(runtime::bound_reached(d20, -9.999) == runtime::BoundSide::lower);  // 1e-3 of 20: 5e-5 of the width
  CHECK(runtime::bound_reached(d20, 9.99) == runtime::BoundSide::none);     // 5e-4 of the width
  CHECK(runtime::bound_reached(d20, 0.0) == runtime::BoundSide::none);
}

TEST_CASE("a parameter without bounds is at none") {
  lang::Parameter fixed;
  fixed.lower = fixed.upper = 1.0;
  CHECK(runtime::bound_reached(fixed, 1.0) == runtime::BoundSide::none);
}

}  // namespace parameter_bounds_test
