// The shooting's Newton step (pwl_fixed_point.cpp) against independent solves: the fixed point
// of X -> Y + J (X - X0) by a full-pivoting LU of J - I in dynamic storage where that is
// regular (the closed-form inverse at the size 4, the LU at 6), and the least-norm solution by
// the SVD's pseudo-inverse where J has an eigenvalue 1 (a direction the map leaves in place).
#include "runtime/closed_form/pwl_fixed_point.hpp"

#include <doctest/doctest.h>
#include <Eigen/LU>
#include <Eigen/SVD>

#include <cmath>

namespace pwl_fixed_point_test {

using namespace rheo;

namespace {

// A map of size N with entries of order 1 and eigenvalues away from 1 (a contraction plus a
// rotation-like coupling), and Y = J X0 + b.
runtime::PwlMatrix map_of(int n, double scale) {
  runtime::PwlMatrix J(n, n);
  for (int r = 0; r < n; ++r)
    for (int c = 0; c < n; ++c) J(r, c) = scale * std::sin(1.3 * r + 0.7 * c + 0.2);
  return J;
}

runtime::PwlVector vector_of(int n, double phase) {
  runtime::PwlVector v(n);
  for (int i = 0; i < n; ++i) v[i] = std::cos(phase + 0.9 * i);
  return v;
}

// The least-norm fixed point X0 - pinv(J - I) (Y - X0) by Eigen's SVD at the rank threshold
// 1e-10: the second path the solver is checked against.
Eigen::VectorXd least_norm_by_svd(const runtime::PwlMatrix& J, const runtime::PwlVector& X0, const runtime::PwlVector& Y) {
  const Eigen::Index n = J.rows();
  const Eigen::MatrixXd J_minus_I = Eigen::MatrixXd(J) - Eigen::MatrixXd::Identity(n, n);
  return Eigen::VectorXd(X0) - J_minus_I.jacobiSvd(Eigen::ComputeThinU | Eigen::ComputeThinV).setThreshold(1e-10).solve(Eigen::VectorXd(Y - X0));
}

}  // namespace

TEST_CASE("least_norm_fixed_point solves the Newton step of a regular map at sizes 4 and 6") {
  for (int n : {4, 6}) {
    for (double scale : {0.4, 3.0, -1.7}) {
      const runtime::PwlMatrix J = map_of(n, scale);
      const runtime::PwlVector X0 = vector_of(n, 0.3), Y = vector_of(n, 2.1);
      const Eigen::MatrixXd J_minus_I = Eigen::MatrixXd(J) - Eigen::MatrixXd::Identity(n, n);
      const Eigen::VectorXd expected = Eigen::VectorXd(X0) - J_minus_I.fullPivLu().solve(Eigen::VectorXd(Y - X0));
      const runtime::PwlVector X = runtime::least_norm_fixed_point(J, X0, Y);
      CAPTURE(n);
      CAPTURE(scale);
      REQUIRE(X.size() == n);
      CHECK((Eigen::VectorXd(X) - expected).cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + expected.cwiseAbs().maxCoeff()));
      // And it is the fixed point: Y + J (X - X0) = X.
      CHECK((Y + J * (X - X0) - X).cwiseAbs().maxCoeff() <= 1e-12 * (1.0 + expected.cwiseAbs().maxCoeff()));
    }
  }
}

TEST_CASE("least_norm_fixed_point takes the least-norm step where J has an eigenvalue 1 at sizes 4 and 6") {
  for (int n : {4, 6}) {
    // J = I + Q D Q^T with D's first entry 0: the first direction is left in place.
    runtime::PwlMatrix Q = map_of(n, 1.0);
    Q = Eigen::MatrixXd(Q).householderQr().householderQ();
    Eigen::VectorXd d(n);
    for (int i = 0; i < n; ++i) d[i] = i == 0 ? 0.0 : -0.5 - 0.3 * i;
    const runtime::PwlMatrix J = Eigen::MatrixXd::Identity(n, n) + Eigen::MatrixXd(Q) * d.asDiagonal() * Eigen::MatrixXd(Q).transpose();
    const runtime::PwlVector X0 = vector_of(n, 0.3), Y = vector_of(n, 2.1);
    const Eigen::VectorXd expected = least_norm_by_svd(J, X0, Y);
    const runtime::PwlVector X = runtime::least_norm_fixed_point(J, X0, Y);
    CAPTURE(n);
    REQUIRE(X.size() == n);
    CHECK((Eigen::VectorXd(X) - expected).cwiseAbs().maxCoeff() <= 1e-10 * (1.0 + expected.cwiseAbs().maxCoeff()));
  }
}

// J - I of a stiff, nearly undamped node's half-period map in the shooting's scales (a column of
// 2e-9 kg behind 1232 N/mm at 0.86 Hz, pwl_periodic_test): regular, but its rows differ by 1e6
// and its unscaled 1-norm condition is 1e-12. The rank-revealing solve with its threshold of 1e-10
// takes it for rank 3 and leaves the step near zero; the step must be the solution, here about
// 1 in the velocity. At the size 6 the same block beside a regular 2 x 2 one (the LU path).
TEST_CASE("least_norm_fixed_point solves a regular map whose rows differ by 1e6 as the regular map it is") {
  Eigen::Matrix4d stiff;
  stiff << -1, 0, 0, 0, -0.314948, -0.685052, 0, -8.13516e-08, 0, 0, 0, 0, -1.54272e+06, 1.54272e+06, 0, -0.685051;
  for (int n : {4, 6}) {
    runtime::PwlMatrix J = runtime::PwlMatrix::Zero(n, n);
    J.topLeftCorner(4, 4) = stiff;
    if (n == 6) J.bottomRightCorner(2, 2) << 0.3, -0.4, 0.5, 0.2;
    runtime::PwlVector X0 = runtime::PwlVector::Zero(n), Y = runtime::PwlVector::Zero(n);
    X0.head(4) << 4.80468e-07, -6.11795e-07, 1, 0;
    Y.head(4) << -4.80468e-07, 3.4914e-07, 1, 3.09454e-10;
    if (n == 6) X0.tail(2) << 0.1, -0.2, Y.tail(2) << 0.3, 0.1;
    const Eigen::MatrixXd J_minus_I = Eigen::MatrixXd(J) - Eigen::MatrixXd::Identity(n, n);
    const Eigen::VectorXd expected = Eigen::VectorXd(X0) - J_minus_I.fullPivLu().solve(Eigen::VectorXd(Y - X0));
    const runtime::PwlVector X = runtime::least_norm_fixed_point(J, X0, Y);
    CAPTURE(n);
    REQUIRE(X.size() == n);
    CHECK(std::abs(expected[3]) > 0.5);  // the velocity's step is of order 1 (the rank-3 solve left it near 0)
    CHECK((Eigen::VectorXd(X) - expected).cwiseAbs().maxCoeff() <= 1e-8);
  }
}

// J - I exactly singular (a coordinate whose end the map does not move: a zero row): the
// closed-form inverse gives infinite and NaN entries, the LU no inverse; both must fail the
// condition test and leave the least-norm solution, finite.
TEST_CASE("least_norm_fixed_point takes the least-norm step where J - I has a zero row, at sizes 4 and 6") {
  for (int n : {4, 6}) {
    runtime::PwlMatrix J = map_of(n, 0.4);
    J.row(0).setZero();
    J(0, 0) = 1.0;
    const runtime::PwlVector X0 = vector_of(n, 0.3), Y = vector_of(n, 2.1);
    const Eigen::VectorXd expected = least_norm_by_svd(J, X0, Y);
    const runtime::PwlVector X = runtime::least_norm_fixed_point(J, X0, Y);
    CAPTURE(n);
    REQUIRE(X.size() == n);
    REQUIRE(X.allFinite());
    CHECK((Eigen::VectorXd(X) - expected).cwiseAbs().maxCoeff() <= 1e-10 * (1.0 + expected.cwiseAbs().maxCoeff()));
  }
}

}  // namespace pwl_fixed_point_test
