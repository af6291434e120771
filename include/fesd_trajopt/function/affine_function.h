#pragma once

#include <Eigen/Sparse>

#include "fesd_trajopt/function/smooth_function.h"

namespace fesd {

/// y = A z + b with a sparse A: exact Jacobian A, zero Hessian.
class AffineFunction : public SmoothFunction {
 public:
  AffineFunction(const Eigen::SparseMatrix<double>& matrix, Eigen::VectorXd offset);

  int inputSize() const override { return static_cast<int>(matrix_.cols()); }
  int outputSize() const override { return static_cast<int>(matrix_.rows()); }
  void evaluate(const double* z, double* y) const override;
  const SparsityPattern& jacobianPattern() const override { return jacobian_pattern_; }
  void evaluateJacobian(const double* z, double* values) const override;
  const SparsityPattern& hessianPattern() const override { return hessian_pattern_; }
  void evaluateHessian(const double*, const double*, double*) const override {}

 private:
  Eigen::SparseMatrix<double, Eigen::RowMajor> matrix_;
  Eigen::VectorXd offset_;
  SparsityPattern jacobian_pattern_, hessian_pattern_;
};

}  // namespace fesd
