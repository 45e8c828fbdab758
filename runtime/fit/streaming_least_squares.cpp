#include "runtime/fit/streaming_least_squares.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace rheo::runtime {

StreamingLeastSquares::StreamingLeastSquares(Eigen::Index columns, Eigen::Index block)
    : n_(columns), block_(block), stack_(RowMajor::Zero(columns + 1 + block, columns + 1)) {
  if (columns < 1 || block < 1) throw std::logic_error("StreamingLeastSquares: at least one column and one row a block");
}

double* StreamingLeastSquares::next_row() {
  if (held_ == block_) reduce();
  double* row = stack_.row(n_ + 1 + held_).data();
  std::fill(row, row + n_ + 1, 0.0);
  ++held_;
  ++rows_;
  return row;
}

void StreamingLeastSquares::reduce() {
  if (held_ == 0) return;
  // [R_old; block] = Q R_new: R_new^T R_new = R_old^T R_old + block^T block, so the factor of
  // every row so far.
  qr_.compute(stack_.topRows(n_ + 1 + held_));
  stack_.topRows(n_ + 1) = qr_.matrixQR().topRows(n_ + 1).triangularView<Eigen::Upper>();
  held_ = 0;
}

Eigen::MatrixXd StreamingLeastSquares::r() {
  reduce();
  return stack_.topLeftCorner(n_, n_);
}

Eigen::VectorXd StreamingLeastSquares::c() {
  reduce();
  return stack_.col(n_).head(n_);
}

double StreamingLeastSquares::rest() {
  reduce();
  return std::abs(stack_(n_, n_));
}

}  // namespace rheo::runtime
