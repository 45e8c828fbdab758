// solve_monotone (runtime/network/monotone_solve.hpp): exact on linear functions, left and right
// ends of a flat zero set, and bounded: an exhausted bound is NaN, never a hang or a value.
#include "runtime/network/monotone_solve.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>

namespace monotone_solve_test {

using rheo::runtime::ForceSlope;
using rheo::runtime::solve_monotone;

TEST_CASE("solve_monotone: a linear function in one Newton step, a flat zero set at either end") {
  int calls = 0;
  auto linear = [&](double x) {
    ++calls;
    return ForceSlope{3.0 * x - 7.0, 3.0};
  };
  CHECK(solve_monotone(linear, 0.0, 1.0, -INFINITY, INFINITY, 1e-14) == doctest::Approx(7.0 / 3.0).epsilon(1e-15));
  CHECK(calls <= 3);
  auto flat = [](double x) { return ForceSlope{x < 1.0 ? x - 1.0 : x > 2.0 ? x - 2.0 : 0.0, x < 1.0 || x > 2.0 ? 1.0 : 0.0}; };
  CHECK(solve_monotone(flat, -5.0, 1.0, -INFINITY, INFINITY, 0.0, true) == doctest::Approx(1.0).epsilon(1e-14));
  CHECK(solve_monotone(flat, 5.0, 1.0, -INFINITY, INFINITY, 0.0, false) == doctest::Approx(2.0).epsilon(1e-14));
}

TEST_CASE("solve_monotone: no root, or a cap too small, is NaN after a bounded number of evaluations") {
  int calls = 0;
  auto never = [&](double x) {  // increasing, below zero everywhere
    ++calls;
    return ForceSlope{std::atan(x) - 2.0, 1.0 / (1.0 + x * x)};
  };
  CHECK(std::isnan(solve_monotone(never, 0.0, 1.0, -INFINITY, INFINITY, 0.0)));
  CHECK(calls <= rheo::runtime::kBracketSteps + rheo::runtime::kRefineSteps + 2);
  calls = 0;
  auto cubic = [&](double x) {
    ++calls;
    return ForceSlope{x * x * x - 2.0, 3.0 * x * x};
  };
  CHECK(std::isnan(solve_monotone(cubic, 0.0, 1.0, -INFINITY, INFINITY, 0.0, true, 1)));
  CHECK(calls < 50);
  CHECK(solve_monotone(cubic, 0.0, 1.0, -INFINITY, INFINITY, 1e-15) == doctest::Approx(std::cbrt(2.0)).epsilon(1e-14));
}

}  // namespace monotone_solve_test
