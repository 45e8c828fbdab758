// Linear least squares over rows that arrive a block at a time (a long history's samples), in
// memory that does not grow with their number.
//
// For the m x n system A x ~ b it keeps the triangular factor of the augmented matrix [A | b]:
// each block of rows is stacked under the factor so far and reduced by a Householder QR (the
// tall-skinny QR, TSQR, of the rows in blocks), so that with R (n x n, upper triangular), c (n)
// and rest >= 0 from the final (n + 1) x (n + 1) factor
//   || A x - b ||^2 = || R x - c ||^2 + rest^2   for every x.
// A minimiser of either side is one of the other (bounded or not: bounded_least_squares.hpp on
// (R, c) solves the box problem of (A, b)), and J = A has the singular values and right
// singular vectors of R (fit_statistics.hpp). Householder reductions are backward stable: R is
// the factor of a matrix within a few eps ||[A b]|| of [A b], as a QR of the whole matrix is;
// the normal equations A^T A, whose condition is squared, are never formed.
// Cost: O(m n^2) flops, (block + n + 1) (n + 1) doubles.
#pragma once

#include <Eigen/Dense>

#include <cstddef>

namespace rheo::runtime {

class StreamingLeastSquares {
 public:
  // COLUMNS: n >= 1; BLOCK: the rows held before each reduction (>= 1).
  explicit StreamingLeastSquares(Eigen::Index columns, Eigen::Index block = 512);

  // The next row of [A | b]: n entries a, then b. Returns where to write them (n + 1 doubles,
  // zeroed, valid until the next call).
  double* next_row();
  // Reduces the rows held (called by the accessors below; next_row calls it when the block is full).
  void reduce();

  Eigen::Index columns() const { return n_; }
  std::size_t rows() const { return rows_; }  // m, the rows given so far
  // R (n x n upper triangular) and c (n), after every row given.
  Eigen::MatrixXd r();
  Eigen::VectorXd c();
  // rest = min_x || A x - b ||, the part of b outside A's column space.
  double rest();

 private:
  using RowMajor = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;
  Eigen::Index n_, block_;
  RowMajor stack_;         // rows 0..n: the factor of [A | b] so far; then the block's rows
  Eigen::Index held_ = 0;  // rows of the block written
  std::size_t rows_ = 0;
  Eigen::HouseholderQR<Eigen::MatrixXd> qr_;
};

}  // namespace rheo::runtime
