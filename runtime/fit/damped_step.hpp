// Levenberg-Marquardt's damped steps for one Jacobian (levenberg_marquardt.hpp), all from one
// factorisation of it.
//
// With J = Q R (Householder; Q orthonormal columns, k = min(m, n) of them, R k x n),
//   || J d + r ||^2 = || R d + Q^T r ||^2 + (|| r ||^2 - || Q^T r ||^2),
// the last term not depending on d. The damped step
//   d = argmin || J d + r ||^2 + lambda || D d ||^2   subject to   lower <= d <= upper
// is therefore the bounded least-squares problem of the k + n rows [R; sqrt(lambda) D] and
// [-Q^T r; 0] (bounded_least_squares.hpp), whatever m is (hundreds of harmonic terms, thousands of
// history samples). For lambda > 0 that problem is strictly convex: its unconstrained minimiser
// is found first, reducing [R; sqrt(lambda) D] to triangular form by Givens rotations (More 1978,
// MINPACK's qrsolv: O(n^3) per lambda); where it lies within the box it is the bounded
// minimiser too (no bound active), else the bounded solver runs on those rows.
#pragma once

#include <Eigen/Dense>

namespace rheo::runtime {

// A step d and the decrease of phi = || r ||^2 the linear model predicts for it,
// || r ||^2 - || J d + r ||^2.
struct DampedStep {
  Eigen::VectorXd d;
  double predicted = 0.0;
  bool bounded = false;  // found by the bounded solver (the unconstrained minimiser left the box, or lambda = 0)
};

class DampedSteps {
 public:
  // J (m x n, finite) and r (m); both are copied. With m >= kSplitRows n, J's rows are reduced
  // in two blocks, side by side on up to `threads` threads (parallel_for.hpp); the result does
  // not depend on `threads`.
  static constexpr Eigen::Index kSplitRows = 8;
  DampedSteps(const Eigen::MatrixXd& j, const Eigen::VectorXd& r, int threads = 1);

  // The damped step for lambda >= 0 and column scales D (n, positive) within lower <= d <= upper
  // (lower <= 0 <= upper). lambda = 0: the bounded Gauss-Newton step (a minimum-norm one, in
  // column-scaled coordinates, where R is rank-deficient).
  // `start`: where the bounded solver begins, if it runs (bounded_least_squares.hpp; empty: at
  // zero), for lambda = 0; for lambda > 0 it begins from the unconstrained minimiser. The
  // minimum value does not depend on it; the minimiser does only where lambda = 0 and R is
  // rank-deficient.
  DampedStep step(double lambda, const Eigen::VectorXd& scale, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                  const Eigen::VectorXd& start = {}) const;

  // The unconstrained minimiser of || [R; sqrt(lambda) D] d + [Q^T r; 0] ||, lambda > 0, by Givens
  // rotations on R (no bound).
  Eigen::VectorXd unconstrained(double lambda, const Eigen::VectorXd& scale) const;

  // || Q^T r ||^2: no step, bounded or not, damped or not, is predicted to lower phi by more.
  double decrease_bound() const { return projected_.squaredNorm(); }

 private:
  Eigen::MatrixXd j_;
  Eigen::VectorXd r_;
  Eigen::MatrixXd reduced_;    // R, k x n
  Eigen::VectorXd projected_;  // Q^T r, k
};

}  // namespace rheo::runtime
