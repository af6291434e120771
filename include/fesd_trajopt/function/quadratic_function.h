#pragma once

#include <memory>
#include <vector>

#include <Eigen/Sparse>

#include "fesd_trajopt/function/smooth_function.h"

namespace fesd {

/// The scalar y = 1/2 z^T Q z + q^T z + r with a sparse symmetric Q.
class QuadraticFunction : public SmoothFunction {
 public:
  QuadraticFunction(const Eigen::SparseMatrix<double>& q_matrix, Eigen::VectorXd q_vector,
                    double constant);
  /// (z - reference)^T W (z - reference) with a diagonal weight W (a tracking cost).
  static std::shared_ptr<QuadraticFunction> weightedDistance(const Eigen::VectorXd& weights,
                                                             const Eigen::VectorXd& reference);

  int inputSize() const override { return static_cast<int>(q_vector_.size()); }
  int outputSize() const override { return 1; }
  void evaluate(const double* z, double* y) const override;
  const SparsityPattern& jacobianPattern() const override { return jacobian_pattern_; }
  void evaluateJacobian(const double* z, double* values) const override;
  const SparsityPattern& hessianPattern() const override { return hessian_pattern_; }
  void evaluateHessian(const double* z, const double* weights, double* values) const override;

 private:
  Eigen::SparseMatrix<double> q_matrix_;
  Eigen::VectorXd q_vector_;
  double constant_;
  SparsityPattern jacobian_pattern_, hessian_pattern_;
  std::vector<double> hessian_values_;  ///< lower triangle of Q in pattern order
};

}  // namespace fesd
