// Bounded-variable linear least squares (BVLS; Stark & Parker 1995, the box form of
// Lawson & Hanson's NNLS):
//
//   minimise || A x - b ||_2   subject to   lower <= x <= upper   (componentwise)
//
// Active-set method: variables at a bound stay there while the gradient g = A^T (b - A x)
// pushes them outwards (g_j <= 0 at a lower bound, g_j >= 0 at an upper one); the others solve
// the unconstrained problem on their columns (column-scaled, rank-revealing QR: a minimum-norm
// answer where columns are dependent); a step that would leave the box stops at the first bound
// met. The loop ends at the Kuhn-Tucker point, which is the global minimum (the problem is
// convex), or after 10 (n + 1) changes of the active set (then the best feasible point found).
// Bounds may be infinite; lower <= upper and finite A, b are required (std::invalid_argument
// otherwise, as for mismatched sizes).
#pragma once

#include <Eigen/Dense>

namespace rheo::runtime {

struct BoundedLeastSquares {
  Eigen::VectorXd x;
  double residual_norm = 0.0;  // || A x - b ||
  int iterations = 0;          // active-set changes
  bool converged = false;      // the Kuhn-Tucker conditions hold (to rounding)
};

// `start` (clipped into the box) is where the search begins; empty: every variable at the
// bound nearer zero (zero where the box holds it).
BoundedLeastSquares bounded_least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& lower,
                                          const Eigen::VectorXd& upper, const Eigen::VectorXd& start = {});

}  // namespace rheo::runtime
