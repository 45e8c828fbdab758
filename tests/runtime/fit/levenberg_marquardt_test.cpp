// Bounded Levenberg-Marquardt (runtime/fit/levenberg_marquardt.hpp) on problems whose minimum is
// known in closed form or by an independent one-dimensional search.
#include "runtime/fit/levenberg_marquardt.hpp"

#include "runtime/core/errors.hpp"

#include <doctest/doctest.h>

#include <cmath>
#include <limits>

namespace levenberg_marquardt_test {

using namespace rheo::runtime;
using Eigen::VectorXd;

namespace {

const double inf = std::numeric_limits<double>::infinity();

VectorXd vec(std::initializer_list<double> values) {
  VectorXd v(static_cast<Eigen::Index>(values.size()));
  Eigen::Index i = 0;
  for (double x : values) v(i++) = x;
  return v;
}

// y = a exp(-b t) at t = 0, 0.25, ..., 3 with a = 2, b = 0.5, plus a fixed, non-smooth wiggle so
// that the minimum has residuals left.
struct Decay {
  VectorXd t = VectorXd::LinSpaced(13, 0.0, 3.0);
  VectorXd y = (2.0 * (-0.5 * t.array()).exp() + 0.01 * (7.0 * t.array()).sin()).matrix();
  VectorXd residuals(const VectorXd& p) const { return (p(0) * (-p(1) * t.array()).exp()).matrix() - y; }
  // With a held, the best b by golden-section search (an independent second path).
  double best_b(double a) const {
    double lo = 0.0, hi = 5.0;
    const double g = (std::sqrt(5.0) - 1.0) / 2.0;
    for (int it = 0; it < 200; ++it) {
      const double x1 = hi - g * (hi - lo), x2 = lo + g * (hi - lo);
      if (residuals(vec({a, x1})).squaredNorm() < residuals(vec({a, x2})).squaredNorm()) hi = x2;
      else lo = x1;
    }
    return 0.5 * (lo + hi);
  }
};

}  // namespace

TEST_CASE("Rosenbrock's valley as residuals: the minimum (1, 1) from (-1.2, 1)") {
  LeastSquaresProblem p;
  p.residuals = [](const VectorXd& x) { return vec({10.0 * (x(1) - x(0) * x(0)), 1.0 - x(0)}); };
  const auto r = levenberg_marquardt(p, vec({-1.2, 1.0}), vec({-inf, -inf}), vec({inf, inf}), {});
  CAPTURE(r.status);
  CHECK(std::abs(r.x(0) - 1.0) < 1e-8);
  CHECK(std::abs(r.x(1) - 1.0) < 1e-8);
  CHECK(r.value < 1e-20);
  CHECK(r.iterations < 40);
}

TEST_CASE("a straight line through scattered points: the normal equations' solution, residuals left") {
  const VectorXd t = VectorXd::LinSpaced(9, 0.0, 8.0);
  const VectorXd y = vec({1.1, 2.9, 5.2, 6.8, 9.1, 11.0, 12.7, 15.3, 16.9});
  LeastSquaresProblem p;
  p.residuals = [&](const VectorXd& x) { return VectorXd((x(0) + x(1) * t.array()).matrix() - y); };
  const auto r = levenberg_marquardt(p, vec({0.0, 0.0}), vec({-inf, -inf}), vec({inf, inf}), {});
  Eigen::MatrixXd a(9, 2);
  a.col(0).setOnes();
  a.col(1) = t;
  const VectorXd exact = (a.transpose() * a).ldlt().solve(a.transpose() * y);
  CAPTURE(r.status);
  CHECK(std::abs(r.x(0) - exact(0)) < 1e-7);
  CHECK(std::abs(r.x(1) - exact(1)) < 1e-7);
  CHECK(r.value == doctest::Approx((a * exact - y).squaredNorm()).epsilon(1e-10).scale(0.0));
  CHECK(r.status == "FTOL_REACHED");
}

TEST_CASE("a bound that binds: the minimum on the face, as a one-dimensional search along it finds it") {
  const Decay d;
  LeastSquaresProblem p;
  p.residuals = [&](const VectorXd& x) { return d.residuals(x); };
  SUBCASE("free: near the generating values") {
    const auto r = levenberg_marquardt(p, vec({1.0, 2.0}), vec({0.0, 0.0}), vec({10.0, 5.0}), {});
    CHECK(std::abs(r.x(0) - 2.0) < 0.02);
    CHECK(std::abs(r.x(1) - 0.5) < 0.02);
    CHECK(std::abs(r.x(1) - d.best_b(r.x(0))) < 1e-7);
  }
  SUBCASE("a <= 1.5") {
    const auto r = levenberg_marquardt(p, vec({1.0, 2.0}), vec({0.0, 0.0}), vec({1.5, 5.0}), {});
    CAPTURE(r.status);
    CHECK(r.x(0) == 1.5);
    // phi stops within its relative tolerance (1e-10) of the face's minimum.
    const double best = d.residuals(vec({1.5, d.best_b(1.5)})).squaredNorm();
    CHECK(r.value >= best * (1.0 - 1e-12));
    CHECK(r.value <= best * (1.0 + 1e-10));
    CHECK(std::abs(r.x(1) - d.best_b(1.5)) < 1e-5);
  }
  SUBCASE("a start outside the box is moved into it") {
    const auto r = levenberg_marquardt(p, vec({9.0, -3.0}), vec({0.0, 0.0}), vec({1.5, 5.0}), {});
    CHECK(r.x(0) == 1.5);
    CHECK(std::abs(r.x(1) - d.best_b(1.5)) < 1e-5);
  }
}

TEST_CASE("a given Jacobian is used instead of differences, and gives the same minimum") {
  const Decay d;
  int jacobians = 0, residual_calls = 0;
  LeastSquaresProblem p;
  p.residuals = [&](const VectorXd& x) {
    ++residual_calls;
    return d.residuals(x);
  };
  p.jacobian = [&](const VectorXd& x, const VectorXd&) {
    ++jacobians;
    Eigen::MatrixXd j(d.t.size(), 2);
    j.col(0) = (-x(1) * d.t.array()).exp().matrix();
    j.col(1) = (-x(0) * d.t.array() * (-x(1) * d.t.array()).exp()).matrix();
    return j;
  };
  const auto r = levenberg_marquardt(p, vec({1.0, 2.0}), vec({0.0, 0.0}), vec({10.0, 5.0}), {});
  CHECK(jacobians == r.iterations);
  CHECK(residual_calls < 2 * r.iterations + 2);  // the start and about one trial per Jacobian: no difference quotients
  CHECK(std::abs(r.x(1) - d.best_b(r.x(0))) < 1e-8);
}

TEST_CASE("residuals that cannot be evaluated reject the step, at the start they are an error") {
  // r = x - 3 has its minimum at 3, but the model cannot be evaluated beyond x = 2.
  LeastSquaresProblem p;
  p.residuals = [](const VectorXd& x) {
    if (x(0) > 2.5) throw NumericalError("beyond the model's range");
    if (x(0) > 2.0) return vec({std::numeric_limits<double>::quiet_NaN()});
    return vec({x(0) - 3.0});
  };
  const auto r = levenberg_marquardt(p, vec({0.0}), vec({-10.0}), vec({10.0}), {});
  CHECK(std::isfinite(r.value));
  CHECK(r.x(0) <= 2.0);
  CHECK(r.x(0) > 1.9);  // it backs up towards the edge of what can be evaluated
  CHECK_THROWS_AS(levenberg_marquardt(p, vec({2.2}), vec({-10.0}), vec({10.0}), {}), NumericalError);
}

TEST_CASE("residuals at rounding level end the search at once") {
  LeastSquaresProblem p;
  int calls = 0;
  p.residuals = [&](const VectorXd& x) {
    ++calls;
    return VectorXd(x);
  };
  const auto r = levenberg_marquardt(p, vec({1e-16, 0.0}), vec({-1.0, -1.0}), vec({1.0, 1.0}), {});
  CHECK(r.status == "STOPVAL_REACHED");
  CHECK(calls == 1);
}

// r = x^3 from x = 1: each near-Gauss-Newton step takes x to about 2x/3, so phi = x^6 falls by
// about 1 - (2/3)^6 = 91 % a Jacobian (less once the damping, scaled by the first Jacobian,
// shortens the steps). A crawl tolerance above that share ends the search after its first step;
// one below it lets it go on, and none further towards 0.
TEST_CASE("a crawl tolerance ends the search where a Jacobian's step gains less than that share of phi") {
  LeastSquaresProblem p;
  p.residuals = [](const VectorXd& x) { return vec({x(0) * x(0) * x(0)}); };
  auto run = [&](double crawl) {
    LevenbergMarquardtSettings s;
    s.crawl_tolerance = crawl;
    return levenberg_marquardt(p, vec({1.0}), vec({-inf}), vec({inf}), s);
  };
  const LevenbergMarquardtResult stopped = run(0.95), going = run(0.85), plain = run(0.0);
  CHECK(stopped.status == "FTOL_REACHED");
  CHECK(stopped.iterations == 1);
  CHECK(stopped.x(0) == doctest::Approx(2.0 / 3.0).epsilon(1e-2).scale(0.0));
  CHECK(going.iterations > 3);
  CHECK(std::abs(going.x(0)) < 0.5 * std::abs(stopped.x(0)));
  CHECK(plain.iterations > going.iterations);  // Marquardt's scaling keeps the largest column norm: the steps shrink as J does
  CHECK(std::abs(plain.x(0)) < 1e-3);
}

// r_i = a t_i - y_i + c^4 + 1e-10 (-1)^i c with y = 2 t: from (0, 0) the column of c is
// numerically zero (1e-10 against 5.5 for a: a parameter the residuals feel only through
// solver noise), its gradient noise. Scaled by its own column norm (Marquardt, MINPACK), every
// damped step sent c across its box, where c^4 = 81 made every trial worse, and the damping
// rose until the steps in a were negligible too: the search crawled through all its
// iterations (MAXITER_REACHED, c wandered to 1.8e-3); held for that Jacobian, the search
// solves a in a few.
TEST_CASE("a parameter the residuals do not feel at the start is held: the others still descend") {
  const VectorXd t = VectorXd::LinSpaced(7, 1.0, 4.0);
  VectorXd alternating(7);
  for (Eigen::Index i = 0; i < 7; ++i) alternating(i) = i % 2 == 0 ? 1.0 : -1.0;
  LeastSquaresProblem p;
  p.residuals = [&](const VectorXd& x) {
    return ((x(0) - 2.0) * t.array() + std::pow(x(1), 4) + 1e-10 * x(1) * alternating.array()).matrix().eval();
  };
  const auto r = levenberg_marquardt(p, vec({0.0, 0.0}), vec({-10.0, -3.0}), vec({10.0, 3.0}), {});
  CAPTURE(r.status);
  CHECK(r.x(0) == doctest::Approx(2.0).epsilon(1e-9).scale(0.0));
  CHECK(std::abs(r.x(1)) < 1e-3);
  CHECK(r.value < 1e-18);
  CHECK(r.iterations <= 5);
}

}  // namespace levenberg_marquardt_test
