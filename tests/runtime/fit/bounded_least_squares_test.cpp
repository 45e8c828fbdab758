// bounded_least_squares against an independent answer: every assignment of each variable to
// free / lower / upper, solved and kept when feasible, gives the global minimum of the convex
// problem by enumeration.
#include "runtime/fit/bounded_least_squares.hpp"

#include "portable_random.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <stdexcept>

namespace bounded_least_squares_test {

using namespace rheo;

namespace {

// min ||A x - b|| over the box by enumerating 3^n active sets (small n only).
double enumerated_minimum(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& lo, const Eigen::VectorXd& hi) {
  const int n = static_cast<int>(a.cols());
  int combinations = 1;
  for (int j = 0; j < n; ++j) combinations *= 3;
  double best = std::numeric_limits<double>::infinity();
  for (int code = 0; code < combinations; ++code) {
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    std::vector<int> free;
    int c = code;
    for (int j = 0; j < n; ++j, c /= 3) {
      if (c % 3 == 0) free.push_back(j);
      else x(j) = c % 3 == 1 ? lo(j) : hi(j);
    }
    Eigen::VectorXd rhs = b - a * x;
    Eigen::MatrixXd sub(a.rows(), static_cast<Eigen::Index>(free.size()));
    for (std::size_t k = 0; k < free.size(); ++k) sub.col(static_cast<Eigen::Index>(k)) = a.col(free[k]);
    if (!free.empty()) {
      const Eigen::VectorXd y = sub.colPivHouseholderQr().solve(rhs);
      for (std::size_t k = 0; k < free.size(); ++k) x(free[k]) = y(static_cast<Eigen::Index>(k));
    }
    bool feasible = true;
    for (int j = 0; j < n; ++j) feasible = feasible && x(j) >= lo(j) - 1e-12 && x(j) <= hi(j) + 1e-12;
    if (feasible) best = std::min(best, (a * x - b).norm());
  }
  return best;
}

}  // namespace

TEST_CASE("within a box that does not bind, the answer is the unconstrained least-squares solution") {
  Eigen::MatrixXd a(5, 3);
  a << 1, 2, 0, 0, 1, 1, 3, 0, 1, 1, 1, 1, 2, 0, 5;
  const Eigen::VectorXd b = (Eigen::VectorXd(5) << 1, -2, 3, 0.5, 4).finished();
  const double inf = std::numeric_limits<double>::infinity();
  const auto got = runtime::bounded_least_squares(a, b, Eigen::VectorXd::Constant(3, -inf), Eigen::VectorXd::Constant(3, inf));
  const Eigen::VectorXd want = a.colPivHouseholderQr().solve(b);
  CHECK(got.converged);
  CHECK((got.x - want).norm() < 1e-12 * want.norm());
  CHECK(got.residual_norm == doctest::Approx((a * want - b).norm()).epsilon(1e-12));
}

TEST_CASE("random boxed problems reach the enumerated global minimum, from any start") {
  test::PortableRandom rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = 1 + trial % 5, m = n + 1 + trial % 7;
    Eigen::MatrixXd a(m, n);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < n; ++j) a(i, j) = rng.normal();
    if (trial % 10 == 9 && n > 1) a.col(n - 1) = a.col(0);  // dependent columns
    Eigen::VectorXd b(m), lo(n), hi(n), start(n);
    for (int i = 0; i < m; ++i) b(i) = 3.0 * rng.normal();
    for (int j = 0; j < n; ++j) {
      lo(j) = rng.uniform(-1.0, 1.0);
      hi(j) = lo(j) + 0.1 + std::abs(rng.uniform(-1.0, 1.0));
      start(j) = 5.0 * rng.uniform(-1.0, 1.0);
    }
    const double want = enumerated_minimum(a, b, lo, hi);
    for (const Eigen::VectorXd& from : {Eigen::VectorXd(), start}) {
      const auto got = runtime::bounded_least_squares(a, b, lo, hi, from);
      CAPTURE(trial);
      CHECK(got.converged);
      CHECK(got.residual_norm == doctest::Approx(want).epsilon(1e-9));
      CHECK(((got.x - lo).minCoeff() >= 0.0 && (hi - got.x).minCoeff() >= 0.0));
    }
  }
}

TEST_CASE("non-negative least squares: a variable the data push below zero stays at zero") {
  Eigen::MatrixXd a(3, 2);
  a << 1, 0, 0, 1, 1, 1;
  const Eigen::VectorXd b = (Eigen::VectorXd(3) << 2, -1, 1).finished();
  const double inf = std::numeric_limits<double>::infinity();
  const auto got = runtime::bounded_least_squares(a, b, Eigen::VectorXd::Zero(2), Eigen::VectorXd::Constant(2, inf));
  // x2 = 0: min (x1 - 2)^2 + 1 + (x1 - 1)^2 at x1 = 1.5.
  CHECK(got.x(0) == doctest::Approx(1.5).epsilon(1e-14));
  CHECK(got.x(1) == 0.0);
}

TEST_CASE("mismatched sizes, crossed bounds and non-finite entries are refused") {
  const Eigen::MatrixXd a = Eigen::MatrixXd::Identity(2, 2);
  const Eigen::VectorXd b = Eigen::VectorXd::Ones(2), lo = Eigen::VectorXd::Zero(2), hi = Eigen::VectorXd::Ones(2);
  CHECK_THROWS_AS(runtime::bounded_least_squares(a, Eigen::VectorXd::Ones(3), lo, hi), std::invalid_argument);
  CHECK_THROWS_AS(runtime::bounded_least_squares(a, b, hi, lo * 0.0 - Eigen::VectorXd::Ones(2)), std::invalid_argument);
  Eigen::VectorXd bad = b;
  bad(1) = std::nan("");
  CHECK_THROWS_AS(runtime::bounded_least_squares(a, bad, lo, hi), std::invalid_argument);
}

}  // namespace bounded_least_squares_test
