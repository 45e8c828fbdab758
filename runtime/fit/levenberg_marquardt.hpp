// Bounded Levenberg-Marquardt for least-squares objectives phi(x) = || r(x) ||^2 within a box
// lower <= x <= upper.
//
// Each iteration linearises the residuals at x, r(x + d) ~ r + J d, with J by forward
// differences (stepping into the box; a point that cannot be evaluated is differenced the other
// way) unless the problem gives it, and takes the damped step
//   d = argmin || J d + r ||^2 + lambda || D d ||^2   subject to   lower <= x + d <= upper,
// a bounded linear least-squares problem (bounded_least_squares.hpp), with D the largest column
// norms of J seen so far (Marquardt's scaling as MINPACK keeps it: the step does not depend on
// the units of x). Every step of one Jacobian comes from one QR factorisation of it
// (damped_step.hpp). A step is taken when phi falls; lambda follows the gain ratio rho = (actual
// decrease) / (decrease the linear model predicts) as Nielsen (1999) does:
// lambda *= max(1/3, 1 - (2 rho - 1)^3) after a step, and lambda *= nu, nu *= 2 after a
// rejected one.
//
// It stops (status):
//   "FTOL_REACHED"  the undamped (Gauss-Newton) step within the box predicts a relative decrease
//                   of phi below `decrease_tolerance` (the first-order conditions hold to that
//                   tolerance: a local minimum); or, where the undamped step predicts less than
//                   100 times that, a step lowered phi by less than the tolerance and the linear
//                   model predicted no more (More's test in MINPACK: sloppy directions, whose
//                   differenced Jacobian is noise, can keep the undamped prediction above the
//                   tolerance); or five iterations together lowered phi by less than 100 times
//                   the tolerance (a crawl along a valley of parameters the data do not
//                   determine, which would otherwise take hundreds of Jacobians);
//                   With `crawl_tolerance` > 0, also where a Jacobian's step lowered phi by
//                   less than that share of it (a search whose caller needs phi to a few digits
//                   only, left crawling along a valley);
//   "XTOL_REACHED"  a step moved no coordinate by more than `step_tolerance` relative to
//                   max(|x_j|, typical_j), where the undamped step predicts less than 100 times
//                   the decrease tolerance (a step that heavy damping made short says nothing);
//   "STOPVAL_REACHED" phi at rounding level (1e-28 per residual): nothing left to fit;
//   "NO_DESCENT"    no damping up to lambda = 1e16 lowers phi (rounding-level noise in r);
//   "MAXITER_REACHED" after `max_iterations` Jacobians.
// A residual vector that is not finite, or a residuals call that throws NumericalError, counts
// as a rejected step (a Jacobian column that cannot be differenced either way is zero, and then
// the first-order tests do not stop the search); the residuals at the start must be finite
// (NumericalError otherwise). Any other exception from the callbacks passes through (a
// caller's budget or interrupt).
#pragma once

#include <Eigen/Dense>

#include <cstddef>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace rheo::runtime {

struct LeastSquaresProblem {
  std::function<Eigen::VectorXd(const Eigen::VectorXd& x)> residuals;
  // Optional: the residuals at several independent points (a differenced Jacobian's moved
  // points: all n columns one way, then those that failed the other way, in column order), as
  // `residuals` would give them called on each in turn: entry i empty where that call throws
  // NumericalError or is not finite; an exception of any other kind passes through, as it
  // would from the first point it is thrown for. It may evaluate the points at once; the search
  // is the same whatever it does. Empty: `residuals` on each in turn.
  std::function<std::vector<Eigen::VectorXd>(const std::vector<Eigen::VectorXd>& xs)> residuals_batch;
  // Optional: dr/dx at x, where the residuals are r; a matrix with no columns where it is not
  // available at x. Empty, or no columns: forward differences.
  std::function<Eigen::MatrixXd(const Eigen::VectorXd& x, const Eigen::VectorXd& r)> jacobian;
  // Optional, where no `jacobian` is given, for residuals too many to hold n more vectors of
  // (a long history's): the forward-differenced Jacobian at x with the steps STEPS (step_j = 0:
  // a zero column), given reduced to n rows: R and c with, for the residuals r at x,
  //   || J d + r ||^2 = || R d + c ||^2 + (|| r ||^2 - || c ||^2)   for every d
  // (R the triangular factor of J and c = Q^T r; history_jacobian.hpp). The damped steps need
  // nothing else (damped_step.hpp). nullopt where a moved point cannot be evaluated: the
  // columns are then differenced from `residuals` as without it.
  struct Reduced {
    Eigen::MatrixXd r;  // n x n
    Eigen::VectorXd c;  // n
  };
  std::function<std::optional<Reduced>(const Eigen::VectorXd& x, const Eigen::VectorXd& steps)> reduced_jacobian;
  // Optional, with reduced_jacobian, where even one residual vector is too long to hold: phi(x)
  // alone (NaN or NumericalError where x cannot be evaluated), and `residuals` is not called.
  // A reduced Jacobian that cannot be formed is tried once more with every step reversed where
  // the box allows (else that column is zero); where that fails too the search ends
  // ("NO_DESCENT"). RESIDUAL_COUNT: m, for the rounding floor of phi ("STOPVAL_REACHED").
  std::function<double(const Eigen::VectorXd& x)> value;
  std::size_t residual_count = 0;
};

struct LevenbergMarquardtSettings {
  int max_iterations = 200;
  double decrease_tolerance = 1e-10;  // relative, on phi
  double step_tolerance = 1e-10;      // relative to max(|x_j|, typical_j)
  double crawl_tolerance = 0.0;       // relative, on phi, per Jacobian (FTOL_REACHED above); 0: off
  double difference_step = 1e-7;      // forward differences: h_j = this * max(|x_j|, typical_j)
  Eigen::VectorXd typical;            // the size of each coordinate where x_j is near zero; empty: 1
  int threads = 1;  // each Jacobian's QR on two blocks of rows side by side (damped_step.hpp); the search is the same for every value
};

struct LevenbergMarquardtResult {
  Eigen::VectorXd x;
  Eigen::VectorXd residuals;
  double value = 0.0;  // phi(x) = || r(x) ||^2
  int iterations = 0;  // Jacobians formed
  std::string status;
};

LevenbergMarquardtResult levenberg_marquardt(const LeastSquaresProblem& problem, const Eigen::VectorXd& start, const Eigen::VectorXd& lower,
                                             const Eigen::VectorXd& upper, const LevenbergMarquardtSettings& settings);

}  // namespace rheo::runtime
