#include "fesd_trajopt/function/affine_function.h"

#include <algorithm>
#include <stdexcept>

namespace fesd {

AffineFunction::AffineFunction(const Eigen::SparseMatrix<double>& matrix, Eigen::VectorXd offset)
    : matrix_(matrix), offset_(std::move(offset)) {
  if (offset_.size() != matrix_.rows()) {
    throw std::invalid_argument("AffineFunction: offset size must match the matrix rows");
  }
  matrix_.makeCompressed();
  for (int r = 0; r < matrix_.outerSize(); ++r) {
    for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(matrix_, r); it; ++it) {
      jacobian_pattern_.add(r, static_cast<int>(it.col()));
    }
  }
}

void AffineFunction::evaluate(const double* z, double* y) const {
  Eigen::Map<Eigen::VectorXd>(y, outputSize()) =
      matrix_ * Eigen::Map<const Eigen::VectorXd>(z, inputSize()) + offset_;
}

void AffineFunction::evaluateJacobian(const double*, double* values) const {
  const double* stored = matrix_.valuePtr();
  std::copy(stored, stored + matrix_.nonZeros(), values);
}

}  // namespace fesd
