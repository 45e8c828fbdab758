// Levenberg-Marquardt's damped steps (runtime/fit/damped_step.hpp) against the direct solve of
// the m + n rows [J; sqrt(lambda) D] d = [-r; 0] (no reduction by J's QR, no Givens rotations):
// column-pivoted Householder where no bound binds, bounded_least_squares on those rows where
// one does.
#include "runtime/fit/damped_step.hpp"

#include "portable_random.hpp"
#include "runtime/fit/bounded_least_squares.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>

namespace damped_step_test {

using namespace rheo;
using Eigen::MatrixXd;
using Eigen::VectorXd;

namespace {

const double inf = std::numeric_limits<double>::infinity();

struct Problem {
  MatrixXd j;
  VectorXd r, scale;
};

// M x N, normal entries; column c scaled by 10^(-spread c / N) (units that differ by decades),
// D the column norms as Levenberg-Marquardt keeps them.
Problem random_problem(test::PortableRandom& rng, int m, int n, double spread) {
  Problem p{MatrixXd(m, n), VectorXd(m), VectorXd()};
  for (int i = 0; i < m; ++i) {
    for (int c = 0; c < n; ++c) p.j(i, c) = rng.normal() * std::pow(10.0, -spread * c / n);
    p.r(i) = rng.normal();
  }
  p.scale = p.j.colwise().norm().transpose();
  return p;
}

MatrixXd stacked(const Problem& p, double lambda) {
  MatrixXd a(p.j.rows() + p.j.cols(), p.j.cols());
  a.topRows(p.j.rows()) = p.j;
  a.bottomRows(p.j.cols()) = (std::sqrt(lambda) * p.scale).asDiagonal();
  return a;
}

VectorXd stacked_rhs(const Problem& p) {
  VectorXd b = VectorXd::Zero(p.j.rows() + p.j.cols());
  b.head(p.j.rows()) = -p.r;
  return b;
}

// || J d + r ||^2 + lambda || D d ||^2
double objective(const Problem& p, double lambda, const VectorXd& d) {
  return (p.j * d + p.r).squaredNorm() + lambda * (p.scale.asDiagonal() * d).squaredNorm();
}

}  // namespace

TEST_CASE("damped steps without a binding bound: the Givens reduction of R stacked on sqrt(lambda) D gives the direct solve's step") {
  test::PortableRandom rng(11);
  for (int trial = 0; trial < 120; ++trial) {
    const int n = 1 + trial % 8, m = trial % 3 == 0 ? std::max(1, n - 2) : n + 3 * (trial % 5);  // some with fewer rows than columns
    const Problem p = random_problem(rng, m, n, trial % 2 == 0 ? 0.0 : 6.0);
    const runtime::DampedSteps steps(p.j, p.r);
    for (const double lambda : {1e-3, 1.0, 1e3}) {
      const VectorXd want = stacked(p, lambda).colPivHouseholderQr().solve(stacked_rhs(p));
      const VectorXd got = steps.unconstrained(lambda, p.scale);
      CAPTURE(trial);
      CAPTURE(lambda);
      // Relative to the scaled step: the columns' units differ by up to six decades.
      CHECK((p.scale.asDiagonal() * (got - want)).norm() <= 1e-10 * (p.scale.asDiagonal() * want).norm() + 1e-14);
      const runtime::DampedStep step = steps.step(lambda, p.scale, VectorXd::Constant(n, -inf), VectorXd::Constant(n, inf));
      CHECK(!step.bounded);
      CHECK((step.d - got).norm() == 0.0);
      CHECK(step.predicted == doctest::Approx(p.r.squaredNorm() - (p.j * want + p.r).squaredNorm()).epsilon(1e-9));
    }
  }
}

TEST_CASE("a tiny damping on nearly dependent columns: the step is as good as the direct solve's") {
  test::PortableRandom rng(5);
  for (int trial = 0; trial < 40; ++trial) {
    Problem p = random_problem(rng, 30, 5, 3.0);
    p.j.col(4) = p.j.col(3) * 2.0 + 1e-9 * p.j.col(0);  // two parameters the data barely tell apart
    p.scale = p.j.colwise().norm().transpose();
    const runtime::DampedSteps steps(p.j, p.r);
    for (const double lambda : {1e-12, 1e-8}) {
      const VectorXd want = stacked(p, lambda).colPivHouseholderQr().solve(stacked_rhs(p));
      const VectorXd got = steps.unconstrained(lambda, p.scale);
      CAPTURE(trial);
      CAPTURE(lambda);
      // The minimum value is well determined even where the minimiser is not.
      CHECK(objective(p, lambda, got) <= objective(p, lambda, want) * (1.0 + 1e-10));
      CHECK(objective(p, lambda, got) >= objective(p, lambda, want) * (1.0 - 1e-10));
    }
  }
}

TEST_CASE("where the box binds, or without damping, the step is the bounded solve of the direct rows") {
  test::PortableRandom rng(3);
  int bounded = 0;
  for (int trial = 0; trial < 120; ++trial) {
    const int n = 2 + trial % 5, m = n + 2 + trial % 7;
    const Problem p = random_problem(rng, m, n, 2.0);
    VectorXd lo(n), hi(n);
    for (int c = 0; c < n; ++c) {
      lo(c) = trial % 4 == 0 ? 0.0 : -rng.uniform(0.0, 0.5);  // some with the point at its lower bounds
      hi(c) = rng.uniform(0.0, 0.5);
    }
    const runtime::DampedSteps steps(p.j, p.r);
    for (const double lambda : {0.0, 1e-2, 1.0}) {
      const auto want = runtime::bounded_least_squares(stacked(p, lambda), stacked_rhs(p), lo, hi);
      const runtime::DampedStep got = steps.step(lambda, p.scale, lo, hi);
      CAPTURE(trial);
      CAPTURE(lambda);
      bounded += got.bounded ? 1 : 0;
      CHECK(got.bounded == (lambda == 0.0 || (want.x.array() == lo.array()).any() || (want.x.array() == hi.array()).any()));
      CHECK(((got.d - lo).minCoeff() >= 0.0 && (hi - got.d).minCoeff() >= 0.0));
      CHECK(objective(p, lambda, got.d) == doctest::Approx(objective(p, lambda, want.x)).epsilon(1e-10));
      // No step gains more than || Q^T r ||^2.
      CHECK(got.predicted <= steps.decrease_bound() * (1.0 + 1e-12));
    }
  }
  CHECK(bounded > 200);  // most of the 360 steps meet a bound: the test exercises that path
}

TEST_CASE("the decrease bound is the undamped step's gain where J has full column rank and nothing binds") {
  test::PortableRandom rng(9);
  const Problem p = random_problem(rng, 25, 4, 1.0);
  const runtime::DampedSteps steps(p.j, p.r);
  const VectorXd gauss_newton = p.j.colPivHouseholderQr().solve(-p.r);
  const double gain = p.r.squaredNorm() - (p.j * gauss_newton + p.r).squaredNorm();
  CHECK(steps.decrease_bound() == doctest::Approx(gain).epsilon(1e-12));
  const runtime::DampedStep undamped = steps.step(0.0, p.scale, VectorXd::Constant(4, -inf), VectorXd::Constant(4, inf));
  CHECK(undamped.predicted == doctest::Approx(gain).epsilon(1e-12));
  CHECK(steps.step(1.0, p.scale, VectorXd::Constant(4, -inf), VectorXd::Constant(4, inf)).predicted < gain);
}

TEST_CASE("a column that could not be differenced (zero, with the floor scale) does not move") {
  test::PortableRandom rng(2);
  Problem p = random_problem(rng, 12, 3, 0.0);
  p.j.col(1).setZero();
  p.scale = p.j.colwise().norm().transpose().cwiseMax(1e-300);
  const runtime::DampedSteps steps(p.j, p.r);
  for (const double lambda : {1e-12, 1.0}) {
    const runtime::DampedStep step = steps.step(lambda, p.scale, VectorXd::Constant(3, -inf), VectorXd::Constant(3, inf));
    CHECK(step.d.allFinite());
    CHECK(step.d(1) == 0.0);
    const VectorXd want = stacked(p, lambda).colPivHouseholderQr().solve(stacked_rhs(p));
    CHECK((step.d - want).norm() <= 1e-10 * want.norm());
  }
}

TEST_CASE("tall Jacobians, reduced in two blocks of rows: the direct solve's steps and gain, the same on one thread and two") {
  test::PortableRandom rng(13);
  for (int trial = 0; trial < 20; ++trial) {
    const int n = 2 + trial % 6, m = static_cast<int>(runtime::DampedSteps::kSplitRows) * n + trial % 3 + 10 * (trial % 4);
    const Problem p = random_problem(rng, m, n, 4.0);
    const runtime::DampedSteps one(p.j, p.r, 1), two(p.j, p.r, 2);
    CAPTURE(trial);
    const VectorXd gauss_newton = p.j.colPivHouseholderQr().solve(-p.r);
    CHECK(one.decrease_bound() == doctest::Approx(p.r.squaredNorm() - (p.j * gauss_newton + p.r).squaredNorm()).epsilon(1e-11));
    CHECK(two.decrease_bound() == one.decrease_bound());
    VectorXd lo(n), hi(n);
    for (int c = 0; c < n; ++c) lo(c) = -rng.uniform(0.0, 0.3), hi(c) = rng.uniform(0.0, 0.3);
    for (const double lambda : {0.0, 1e-3, 1.0}) {
      CAPTURE(lambda);
      if (lambda > 0.0) {
        const VectorXd want = stacked(p, lambda).colPivHouseholderQr().solve(stacked_rhs(p));
        const VectorXd got = one.unconstrained(lambda, p.scale);
        CHECK((p.scale.asDiagonal() * (got - want)).norm() <= 1e-10 * (p.scale.asDiagonal() * want).norm());
        CHECK((two.unconstrained(lambda, p.scale) - got).norm() == 0.0);
      }
      const auto want = runtime::bounded_least_squares(stacked(p, lambda), stacked_rhs(p), lo, hi);
      const runtime::DampedStep got = one.step(lambda, p.scale, lo, hi);
      CHECK(objective(p, lambda, got.d) == doctest::Approx(objective(p, lambda, want.x)).epsilon(1e-10));
      CHECK((two.step(lambda, p.scale, lo, hi).d - got.d).norm() == 0.0);
    }
  }
}

}  // namespace damped_step_test
