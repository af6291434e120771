#include "fesd_trajopt/function/quadratic_function.h"

#include <stdexcept>

namespace fesd {

QuadraticFunction::QuadraticFunction(const Eigen::SparseMatrix<double>& q_matrix,
                                     Eigen::VectorXd q_vector, double constant)
    : q_matrix_(q_matrix), q_vector_(std::move(q_vector)), constant_(constant) {
  if (q_matrix_.rows() != q_vector_.size() || q_matrix_.cols() != q_vector_.size()) {
    throw std::invalid_argument("QuadraticFunction: Q must be square and match q");
  }
  if (!q_matrix_.isApprox(Eigen::SparseMatrix<double>(q_matrix_.transpose()))) {
    throw std::invalid_argument("QuadraticFunction: Q must be symmetric");
  }
  q_matrix_.makeCompressed();
  // The gradient Q z + q is structurally nonzero where q or a column of Q is.
  Eigen::VectorXi touched = (q_vector_.array() != 0.0).cast<int>();
  for (int c = 0; c < q_matrix_.outerSize(); ++c) {
    for (Eigen::SparseMatrix<double>::InnerIterator it(q_matrix_, c); it; ++it) {
      touched(c) = 1;
      if (it.row() >= c) {
        hessian_pattern_.add(static_cast<int>(it.row()), c);
        hessian_values_.push_back(it.value());
      }
    }
  }
  for (int c = 0; c < touched.size(); ++c) {
    if (touched(c)) jacobian_pattern_.add(0, c);
  }
}

std::shared_ptr<QuadraticFunction> QuadraticFunction::weightedDistance(
    const Eigen::VectorXd& weights, const Eigen::VectorXd& reference) {
  if (weights.size() != reference.size()) {
    throw std::invalid_argument("weightedDistance: weights and reference differ in size");
  }
  Eigen::SparseMatrix<double> q(weights.size(), weights.size());
  for (int i = 0; i < weights.size(); ++i) {
    if (weights(i) != 0.0) q.insert(i, i) = 2.0 * weights(i);
  }
  const Eigen::VectorXd linear = -2.0 * weights.cwiseProduct(reference);
  const double constant = reference.dot(weights.cwiseProduct(reference));
  return std::make_shared<QuadraticFunction>(q, linear, constant);
}

void QuadraticFunction::evaluate(const double* z, double* y) const {
  const Eigen::Map<const Eigen::VectorXd> zz(z, inputSize());
  y[0] = 0.5 * zz.dot(q_matrix_ * zz) + q_vector_.dot(zz) + constant_;
}

void QuadraticFunction::evaluateJacobian(const double* z, double* values) const {
  const Eigen::Map<const Eigen::VectorXd> zz(z, inputSize());
  const Eigen::VectorXd gradient = q_matrix_ * zz + q_vector_;
  for (int e = 0; e < jacobian_pattern_.nonzeros(); ++e)
    values[e] = gradient(jacobian_pattern_.cols[e]);
}

void QuadraticFunction::evaluateHessian(const double*, const double* weights,
                                        double* values) const {
  for (size_t e = 0; e < hessian_values_.size(); ++e) values[e] = weights[0] * hessian_values_[e];
}

}  // namespace fesd
