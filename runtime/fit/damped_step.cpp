#include "runtime/fit/damped_step.hpp"

#include "runtime/core/parallel_for.hpp"
#include "runtime/fit/bounded_least_squares.hpp"

#include <array>
#include <cmath>
#include <utility>

namespace rheo::runtime {

namespace {

// R and Q^T r of one block of rows (Householder; min(rows, n) of them).
struct Triangle {
  Eigen::MatrixXd r;
  Eigen::VectorXd qtr;
};

Triangle triangle(const Eigen::Ref<const Eigen::MatrixXd>& j, const Eigen::Ref<const Eigen::VectorXd>& r) {
  const Eigen::HouseholderQR<Eigen::MatrixXd> qr(j);
  const Eigen::Index k = std::min(j.rows(), j.cols());
  const Eigen::VectorXd qtr = qr.householderQ().adjoint() * r;
  return {qr.matrixQR().topRows(k).triangularView<Eigen::Upper>(), qtr.head(k)};
}

}  // namespace

DampedSteps::DampedSteps(const Eigen::MatrixXd& j, const Eigen::VectorXd& r, int threads) : j_(j), r_(r) {
  const Eigen::Index m = j.rows(), n = j.cols();
  if (n == 0 || m < kSplitRows * n) {
    Triangle whole = triangle(j, r);
    reduced_ = std::move(whole.r), projected_ = std::move(whole.qtr);
    return;
  }
  // Two blocks of rows, each reduced on its own (side by side on two threads), then their
  // stacked triangles: J = diag(Q1, Q2) [R1; R2] = diag(Q1, Q2) Q3 R (TSQR). The split does not
  // depend on the threads, so neither does R.
  const Eigen::Index half = m / 2;
  std::array<Triangle, 2> blocks;
  parallel_for(2, threads, [&](std::size_t b) {
    blocks[b] = b == 0 ? triangle(j.topRows(half), r.head(half)) : triangle(j.bottomRows(m - half), r.tail(m - half));
  });
  Eigen::MatrixXd stacked(2 * n, n);
  stacked << blocks[0].r, blocks[1].r;
  Eigen::VectorXd stacked_qtr(2 * n);
  stacked_qtr << blocks[0].qtr, blocks[1].qtr;
  Triangle whole = triangle(stacked, stacked_qtr);
  reduced_ = std::move(whole.r), projected_ = std::move(whole.qtr);
}

Eigen::VectorXd DampedSteps::unconstrained(double lambda, const Eigen::VectorXd& scale) const {
  const Eigen::Index k = reduced_.rows(), n = reduced_.cols();
  // S starts as R (zero rows below k where m < n), c as -Q^T r; each row sqrt(lambda) D_j e_j^T
  // (right-hand side 0) is rotated into S's rows j..n-1 in turn, which leaves S upper triangular
  // with S^T S = R^T R + lambda D^2 and the same least-squares minimiser.
  Eigen::MatrixXd s = Eigen::MatrixXd::Zero(n, n);
  s.topRows(k) = reduced_;
  Eigen::VectorXd c = Eigen::VectorXd::Zero(n);
  c.head(k) = -projected_;
  Eigen::VectorXd row(n);
  const double root = std::sqrt(lambda);
  for (Eigen::Index j = 0; j < n; ++j) {
    row.setZero();
    row(j) = root * scale(j);
    double rhs = 0.0;
    for (Eigen::Index i = j; i < n; ++i) {
      if (row(i) == 0.0) continue;
      // The rotation [cs sn; -sn cs] zeroing row(i) against s(i, i) (MINPACK's qrsolv form).
      double cs = 0.0, sn = 0.0;
      if (std::abs(s(i, i)) < std::abs(row(i))) {
        const double cotangent = s(i, i) / row(i);
        sn = 0.5 / std::sqrt(0.25 + 0.25 * cotangent * cotangent);
        cs = sn * cotangent;
      } else {
        const double tangent = row(i) / s(i, i);
        cs = 0.5 / std::sqrt(0.25 + 0.25 * tangent * tangent);
        sn = cs * tangent;
      }
      for (Eigen::Index l = i; l < n; ++l) {
        const double upper = s(i, l), lower = row(l);
        s(i, l) = cs * upper + sn * lower;
        row(l) = -sn * upper + cs * lower;
      }
      const double upper = c(i);
      c(i) = cs * upper + sn * rhs;
      rhs = -sn * upper + cs * rhs;
    }
  }
  return s.triangularView<Eigen::Upper>().solve(c);
}

DampedStep DampedSteps::step(double lambda, const Eigen::VectorXd& scale, const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                             const Eigen::VectorXd& start) const {
  const Eigen::Index k = reduced_.rows(), n = reduced_.cols();
  DampedStep out;
  Eigen::VectorXd from = start;
  if (lambda > 0.0) {
    // Strictly convex: the unconstrained minimiser, where the box holds it, is the bounded one;
    // else the bounded solver starts from it, clipped (the bounds it crossed held).
    out.d = unconstrained(lambda, scale);
    const bool inside = out.d.allFinite() && (out.d.array() >= lower.array()).all() && (out.d.array() <= upper.array()).all();
    if (!inside) {
      if (out.d.allFinite()) from = out.d;
      out.d.resize(0);
    }
  }
  if (out.d.size() == 0) {
    // [R; sqrt(lambda) D] d = [-Q^T r; 0]; without damping the zero rows are left out.
    const Eigen::Index rows = lambda > 0.0 ? k + n : k;
    Eigen::MatrixXd a(rows, n);
    a.topRows(k) = reduced_;
    if (lambda > 0.0) a.bottomRows(n) = (std::sqrt(lambda) * scale).asDiagonal();
    Eigen::VectorXd b = Eigen::VectorXd::Zero(rows);
    b.head(k) = -projected_;
    out.d = bounded_least_squares(a, b, lower, upper, from).x;
    out.bounded = true;
  }
  out.predicted = r_.squaredNorm() - (j_ * out.d + r_).squaredNorm();
  return out;
}

}  // namespace rheo::runtime
