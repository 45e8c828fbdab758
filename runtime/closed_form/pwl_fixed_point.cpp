#include "runtime/closed_form/pwl_fixed_point.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>

namespace rheo::runtime {

using Eigen::MatrixXd;
using Complex = std::complex<double>;

PwlVector affine_fixed_point(const PwlMatrix& J, const PwlVector& X0, const PwlVector& Y) {
  const Eigen::VectorXd b = Y - J * X0;
  Eigen::EigenSolver<MatrixXd> eig(J);
  if (eig.info() == Eigen::Success) {
    const Eigen::MatrixXcd V = eig.eigenvectors();
    const Eigen::VectorXcd lambda = eig.eigenvalues();
    Eigen::FullPivLU<Eigen::MatrixXcd> lu(V);
    if (lu.rcond() > 1e-10) {
      const Eigen::VectorXcd xi0 = lu.solve(X0.cast<Complex>()), beta = lu.solve(b.cast<Complex>());
      Eigen::VectorXcd xi(xi0.size());
      for (Eigen::Index i = 0; i < xi.size(); ++i) xi[i] = std::abs(1.0 - lambda[i]) > 1e-9 ? beta[i] / (1.0 - lambda[i]) : xi0[i];
      return (V * xi).real();
    }
  }
  return X0 - (J - PwlMatrix::Identity(J.rows(), J.cols())).jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).setThreshold(1e-10).solve(Y - X0);
}

namespace {

// The reciprocal condition in the 1-norm of A D^-1, D the diagonal of A's column 1-norms, from
// A's INVERSE: 1 / (||A D^-1|| ||D A^-1||) = 1 / max_j sum_i d_i |A^-1_ij| (||A D^-1|| = 1).
// Scaling the columns leaves the solution of A x = b as it is (x = D^-1 (A D^-1)^-1 b), so that
// only how well A's columns are told apart, not their sizes, decides whether the solve is
// trusted: the map of a stiff, nearly undamped node has rows of order omega_n / omega (1.5e6:
// 2e-9 kg behind 1232 N/mm driven at 0.86 Hz), and the unscaled condition, 1e-12, sent a
// regular system to the rank-revealing solve, which dropped the velocity's column and left
// Newton's step at zero. A singular A gives an infinite or NaN inverse, which fails the test.
template <class Matrix>
double equilibrated_rcond(const Matrix& a, const Matrix& inverse) {
  std::array<double, kPwlMaxDim> d{};  // the column 1-norms of A
  for (Eigen::Index j = 0; j < a.cols(); ++j) {
    d[static_cast<std::size_t>(j)] = a.col(j).cwiseAbs().sum();
    if (!(d[static_cast<std::size_t>(j)] > 0.0)) return 0.0;
  }
  double norm = 0.0;  // ||D A^-1||_1
  for (Eigen::Index j = 0; j < inverse.cols(); ++j) {
    double column = 0.0;
    for (Eigen::Index i = 0; i < inverse.rows(); ++i) column += d[static_cast<std::size_t>(i)] * std::abs(inverse(i, j));
    if (!std::isfinite(column)) return 0.0;  // std::max would pass over a NaN
    norm = std::max(norm, column);
  }
  return 1.0 / norm;
}

// Where J - I is well conditioned the least-norm solution is the solution: by LU (at the size
// 4 by the closed-form inverse below), several
// times cheaper than the orthogonal decomposition. Its reciprocal condition in the 1-norm with
// the columns equilibrated (equilibrated_rcond), from the inverse itself (at most 24 x 24:
// cheaper than the estimator's repeated solves, and exact). False (OUT untouched) where it is
// below 1e-8. (Column equilibration minimises the 1-norm condition over column scalings, van der
// Sluis 1969: every system the unscaled test passed passes it.)
// MATRIX: PwlMatrix, or a fixed size the compiler unrolls.
template <class Matrix>
bool lu_fixed_point(const PwlMatrix& J, const PwlVector& X0, const PwlVector& Y, PwlVector& out) {
  using Vector = Eigen::Matrix<double, Matrix::RowsAtCompileTime, 1, 0, Matrix::MaxRowsAtCompileTime, 1>;
  const Matrix J_minus_I = Matrix(J) - Matrix::Identity(J.rows(), J.cols());
  Eigen::FullPivLU<Matrix> lu(J_minus_I);
  if (!lu.isInvertible()) return false;
  const Matrix inverse = lu.inverse();
  if (!(equilibrated_rcond(J_minus_I, inverse) > 1e-8)) return false;
  const Vector x0 = X0, residual = Vector(Y) - x0;
  out = x0 - lu.solve(residual);
  return true;
}

// The same at the size 4 (a slider-capped column's map), by the closed-form inverse (cofactors):
// a fraction of the LU's work, its error within the condition number times the rounding, as
// the LU's; the reciprocal condition as above (a singular J - I gives an infinite or NaN inverse,
// which fails the test).
bool inverse_fixed_point(const PwlMatrix& J, const PwlVector& X0, const PwlVector& Y, PwlVector& out) {
  const Eigen::Matrix4d J_minus_I = Eigen::Matrix4d(J) - Eigen::Matrix4d::Identity();
  const Eigen::Matrix4d inverse = J_minus_I.inverse();
  if (!(equilibrated_rcond(J_minus_I, inverse) > 1e-8)) return false;
  const Eigen::Vector4d x0 = X0, residual = Eigen::Vector4d(Y) - x0;
  out = x0 - inverse * residual;
  return true;
}

}  // namespace

PwlVector least_norm_fixed_point(const PwlMatrix& J, const PwlVector& X0, const PwlVector& Y) {
  PwlVector out;
  bool solved = false;
  switch (J.rows()) {  // 2 N for N internal nodes: a slider-capped column has 4
    case 4: solved = inverse_fixed_point(J, X0, Y, out); break;
    case 6: solved = lu_fixed_point<Eigen::Matrix<double, 6, 6>>(J, X0, Y, out); break;
    default: solved = lu_fixed_point<PwlMatrix>(J, X0, Y, out); break;
  }
  if (solved) return out;
  const PwlMatrix J_minus_I = J - PwlMatrix::Identity(J.rows(), J.cols());
  Eigen::CompleteOrthogonalDecomposition<PwlMatrix> cod(J_minus_I);
  cod.setThreshold(1e-10);
  return X0 - cod.solve(PwlVector(Y - X0));
}

}  // namespace rheo::runtime
