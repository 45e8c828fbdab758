#include "runtime/fit/optimizer.hpp"

#include "runtime/core/errors.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <stdexcept>

namespace optimizer_test {

using namespace rheo::runtime;

TEST_CASE("minimize finds the minimum of a bounded quadratic, local and global") {
  const Objective f = [](const std::vector<double>& x) { return (x[0] - 1.5) * (x[0] - 1.5) + 3 * (x[1] + 0.5) * (x[1] + 0.5); };
  for (auto algorithm : {Algorithm::bobyqa, Algorithm::sbplx}) {
    OptimizerSettings s;
    s.algorithm = algorithm;
    const auto r = minimize(f, {0.0, 0.0}, {-5, -5}, {5, 5}, s);
    CHECK(r.x[0] == doctest::Approx(1.5).epsilon(1e-6));
    CHECK(r.x[1] == doctest::Approx(-0.5).epsilon(1e-6).scale(0.0));
    CHECK(r.evaluations > 0);
  }
  OptimizerSettings global;
  global.algorithm = Algorithm::crs2;
  global.max_evaluations = 3000;
  const auto a = minimize(f, {0.0, 0.0}, {-5, -5}, {5, 5}, global), b = minimize(f, {0.0, 0.0}, {-5, -5}, {5, 5}, global);
  CHECK(a.x == b.x);  // a fixed seed gives the same result
  CAPTURE(a.status);
  CAPTURE(a.evaluations);
  CHECK(a.value < 1e-3);
}

TEST_CASE("an exception in the objective stops NLopt and is rethrown after it returns") {
  const Objective f = [](const std::vector<double>& x) -> double {
    if (x[0] > 0.5) throw std::runtime_error("boom");
    return x[0];
  };
  CHECK_THROWS_WITH(minimize(f, {1.0}, {0.0}, {2.0}, {}), "boom");
}

TEST_CASE("non-finite objective values are backed away from and counted") {
  const Objective f = [](const std::vector<double>& x) { return x[0] < 0.2 ? std::nan("") : (x[0] - 0.7) * (x[0] - 0.7); };
  const auto r = minimize(f, {1.0}, {0.0}, {2.0}, {});
  CHECK(r.x[0] == doctest::Approx(0.7).epsilon(1e-5).scale(0.0));
  CHECK(std::isfinite(r.value));
}

TEST_CASE("a NaN region beside the start does not derail BOBYQA's model (finite penalty)") {
  // Minimum 0.5 at (2, 2); NaN on the half-plane x0 < -1, which BOBYQA's first steps from the
  // start (-0.8, 0) reach.
  const Objective f = [](const std::vector<double>& x) {
    if (x[0] < -1.0) return std::nan("");
    return 0.5 + (x[0] - 2) * (x[0] - 2) + 4 * (x[1] - 2) * (x[1] - 2);
  };
  const auto r = minimize(f, {-0.8, 0.0}, {-5.0, -5.0}, {5.0, 5.0}, {});
  CHECK(r.non_finite > 0);
  CHECK(r.value == doctest::Approx(0.5).epsilon(1e-9).scale(0.0));
  CHECK(r.x[0] == doctest::Approx(2.0).epsilon(1e-5));
}

}  // namespace optimizer_test
