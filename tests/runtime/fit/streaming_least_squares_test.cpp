// StreamingLeastSquares (runtime/fit/streaming_least_squares.hpp) against Eigen's dense
// least squares of the whole matrix: the same minimiser, minimum, singular values and
// quadratic form || A y - b ||^2 at any y, whatever the block size; fewer rows than columns.
#include "runtime/fit/streaming_least_squares.hpp"

#include "portable_random.hpp"

#include <doctest/doctest.h>

#include <Eigen/Dense>

#include <cmath>

namespace streaming_least_squares_test {

using namespace rheo;

namespace {

// A random m x (n + 1) system [A | b] with columns of unlike scales (1e-3 to 1e3) and a slightly
// collinear pair (1 %).
Eigen::MatrixXd system_of(Eigen::Index m, Eigen::Index n, unsigned seed) {
  test::PortableRandom random(seed);
  Eigen::MatrixXd ab(m, n + 1);
  for (Eigen::Index i = 0; i < m; ++i)
    for (Eigen::Index j = 0; j <= n; ++j) ab(i, j) = random.normal() * std::pow(10.0, static_cast<double>(j % 3) * 3.0 - 3.0);
  if (n >= 2) ab.col(1) = ab.col(0) * 1e3 + 1e-2 * ab.col(1);
  return ab;
}

runtime::StreamingLeastSquares streamed(const Eigen::MatrixXd& ab, Eigen::Index block) {
  runtime::StreamingLeastSquares s(ab.cols() - 1, block);
  for (Eigen::Index i = 0; i < ab.rows(); ++i) {
    double* row = s.next_row();
    for (Eigen::Index j = 0; j < ab.cols(); ++j) row[j] = ab(i, j);
  }
  return s;
}

double relative(double value, double reference) { return std::abs(value - reference) / std::abs(reference); }

}  // namespace

TEST_CASE("streamed least squares: the minimiser, minimum and singular values of the dense solve, for any block size") {
  const Eigen::Index n = 4;
  const Eigen::MatrixXd ab = system_of(3001, n, 7);
  const Eigen::MatrixXd a = ab.leftCols(n);
  const Eigen::VectorXd b = ab.col(n);
  const Eigen::VectorXd x_dense = a.colPivHouseholderQr().solve(b);
  const double rest_dense = (a * x_dense - b).norm();
  const Eigen::VectorXd singular_dense = a.jacobiSvd().singularValues();
  for (const Eigen::Index block : {1, 7, 512, 5000}) {
    CAPTURE(block);
    runtime::StreamingLeastSquares s = streamed(ab, block);
    CHECK(s.rows() == 3001);
    const Eigen::MatrixXd r = s.r();
    const Eigen::VectorXd c = s.c();
    CHECK(r.isUpperTriangular(0.0));
    const Eigen::VectorXd x = r.triangularView<Eigen::Upper>().solve(c);
    for (Eigen::Index j = 0; j < n; ++j) CHECK(relative(x(j), x_dense(j)) < 1e-10);
    CHECK(relative(s.rest(), rest_dense) < 1e-12);
    const Eigen::VectorXd singular = r.jacobiSvd().singularValues();
    for (Eigen::Index k = 0; k < n; ++k) CHECK(relative(singular(k), singular_dense(k)) < 1e-10);
    // The quadratic form everywhere, not only at the minimum.
    const Eigen::VectorXd y = x_dense + Eigen::VectorXd::LinSpaced(n, 0.5, -2.0).cwiseProduct(x_dense.cwiseAbs());
    CHECK(relative((r * y - c).squaredNorm() + s.rest() * s.rest(), (a * y - b).squaredNorm()) < 1e-12);
  }
}

TEST_CASE("streamed least squares with fewer rows than columns: the quadratic form still holds, the rest is zero") {
  const Eigen::MatrixXd ab = system_of(2, 5, 3);
  runtime::StreamingLeastSquares s = streamed(ab, 4);
  const Eigen::VectorXd y = Eigen::VectorXd::LinSpaced(5, -1.0, 3.0);
  CHECK(relative((s.r() * y - s.c()).squaredNorm() + s.rest() * s.rest(), (ab.leftCols(5) * y - ab.col(5)).squaredNorm()) < 1e-13);
  CHECK(s.rest() < 1e-12 * ab.norm());
  CHECK_THROWS_AS(runtime::StreamingLeastSquares(0), std::logic_error);
}

}  // namespace streaming_least_squares_test
