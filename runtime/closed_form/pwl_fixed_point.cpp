#include "runtime/closed_form/pwl_fixed_point.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <Eigen/QR>
#include <Eigen/SVD>

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

// Where J - I is well conditioned the least-norm solution is the solution: by LU (at the size
// 4 by the closed-form inverse below), several
// times cheaper than the orthogonal decomposition. Its reciprocal condition in the 1-norm,
// 1/(||J - I|| ||(J - I)^-1||), from the inverse itself (at most 24 x 24: cheaper than the
// estimator's repeated solves, and exact). False (OUT untouched) where it is below 1e-8.
// MATRIX: PwlMatrix, or a fixed size the compiler unrolls.
template <class Matrix>
bool lu_fixed_point(const PwlMatrix& J, const PwlVector& X0, const PwlVector& Y, PwlVector& out) {
  using Vector = Eigen::Matrix<double, Matrix::RowsAtCompileTime, 1, 0, Matrix::MaxRowsAtCompileTime, 1>;
  const Matrix J_minus_I = Matrix(J) - Matrix::Identity(J.rows(), J.cols());
  Eigen::FullPivLU<Matrix> lu(J_minus_I);
  if (!lu.isInvertible()) return false;
  const Matrix inverse = lu.inverse();
  const double norm = J_minus_I.cwiseAbs().colwise().sum().maxCoeff(), inverse_norm = inverse.cwiseAbs().colwise().sum().maxCoeff();
  if (!(1.0 / (norm * inverse_norm) > 1e-8)) return false;
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
  const double norm = J_minus_I.cwiseAbs().colwise().sum().maxCoeff(), inverse_norm = inverse.cwiseAbs().colwise().sum().maxCoeff();
  if (!(1.0 / (norm * inverse_norm) > 1e-8)) return false;
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
