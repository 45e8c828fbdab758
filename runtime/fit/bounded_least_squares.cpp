#include "runtime/fit/bounded_least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

namespace rheo::runtime {
namespace {

enum class Bound : signed char { lower = -1, none = 0, upper = 1 };

// Least squares on the free columns with the bound variables held: the free variables' values.
Eigen::VectorXd free_solution(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& x, const std::vector<Bound>& at) {
  std::vector<Eigen::Index> free;
  Eigen::VectorXd rhs = b;
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    if (at[static_cast<std::size_t>(j)] == Bound::none) free.push_back(j);
    else rhs -= a.col(j) * x(j);
  }
  if (free.empty()) return x;
  Eigen::MatrixXd sub(a.rows(), static_cast<Eigen::Index>(free.size()));
  Eigen::VectorXd scale(sub.cols());
  for (Eigen::Index k = 0; k < sub.cols(); ++k) {
    sub.col(k) = a.col(free[static_cast<std::size_t>(k)]);
    const double norm = sub.col(k).norm();
    scale(k) = norm > 0.0 ? 1.0 / norm : 1.0;
    sub.col(k) *= scale(k);
  }
  const Eigen::VectorXd y = sub.completeOrthogonalDecomposition().solve(rhs);
  Eigen::VectorXd result = x;
  for (Eigen::Index k = 0; k < sub.cols(); ++k) result(free[static_cast<std::size_t>(k)]) = y(k) * scale(k);
  return result;
}

}  // namespace

BoundedLeastSquares bounded_least_squares(const Eigen::MatrixXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& lower,
                                          const Eigen::VectorXd& upper, const Eigen::VectorXd& start) {
  const Eigen::Index n = a.cols();
  if (b.size() != a.rows() || lower.size() != n || upper.size() != n || (start.size() != 0 && start.size() != n))
    throw std::invalid_argument("bounded_least_squares: sizes of A, b, bounds and start do not agree");
  for (Eigen::Index j = 0; j < n; ++j)
    if (!(lower(j) <= upper(j))) throw std::invalid_argument("bounded_least_squares: a lower bound above its upper bound");
  if (!a.allFinite() || !b.allFinite()) throw std::invalid_argument("bounded_least_squares: A or b holds a NaN or an infinity");

  BoundedLeastSquares out;
  Eigen::VectorXd x = start.size() == n ? start : Eigen::VectorXd::Zero(n);
  std::vector<Bound> at(static_cast<std::size_t>(n), Bound::none);
  for (Eigen::Index j = 0; j < n; ++j) {
    x(j) = std::clamp(x(j), lower(j), upper(j));
    if (x(j) == lower(j) && std::isfinite(lower(j))) at[static_cast<std::size_t>(j)] = Bound::lower;
    else if (x(j) == upper(j) && std::isfinite(upper(j))) at[static_cast<std::size_t>(j)] = Bound::upper;
  }
  const int limit = 10 * static_cast<int>(n + 1);
  const double tiny = 1e-13;
  while (out.iterations < limit) {
    // Move the free variables towards their unconstrained optimum, stopping at the box.
    for (int inner = 0; inner <= n; ++inner) {
      const Eigen::VectorXd target = free_solution(a, b, x, at);
      double step = 1.0;
      Eigen::Index blocking = -1;
      for (Eigen::Index j = 0; j < n; ++j) {
        if (at[static_cast<std::size_t>(j)] != Bound::none || target(j) == x(j)) continue;
        const double limit_j = target(j) < lower(j)   ? (lower(j) - x(j)) / (target(j) - x(j))
                               : target(j) > upper(j) ? (upper(j) - x(j)) / (target(j) - x(j))
                                                      : 1.0;
        if (limit_j < step) step = std::max(0.0, limit_j), blocking = j;
      }
      x += step * (target - x);
      if (blocking < 0) break;
      x(blocking) = target(blocking) < lower(blocking) ? lower(blocking) : upper(blocking);
      at[static_cast<std::size_t>(blocking)] = x(blocking) == lower(blocking) ? Bound::lower : Bound::upper;
      ++out.iterations;
    }
    // Kuhn-Tucker: release the bound variable whose gradient points most into the box.
    const Eigen::VectorXd gradient = a.transpose() * (b - a * x);
    const double gradient_scale = tiny * (a.transpose() * b).cwiseAbs().maxCoeff() + std::numeric_limits<double>::min();
    Eigen::Index release = -1;
    double most = gradient_scale;
    for (Eigen::Index j = 0; j < n; ++j) {
      const double inward = at[static_cast<std::size_t>(j)] == Bound::lower   ? gradient(j)
                            : at[static_cast<std::size_t>(j)] == Bound::upper ? -gradient(j)
                                                                              : 0.0;
      if (inward > most) most = inward, release = j;
    }
    if (release < 0) {
      out.converged = true;
      break;
    }
    at[static_cast<std::size_t>(release)] = Bound::none;
    ++out.iterations;
  }
  out.residual_norm = (a * x - b).norm();
  out.x = std::move(x);
  return out;
}

}  // namespace rheo::runtime
