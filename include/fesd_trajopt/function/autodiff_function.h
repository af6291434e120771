#pragma once

#include <memory>
#include <utility>
#include <vector>

#include <Eigen/Dense>
#include <unsupported/Eigen/AutoDiff>

#include "fesd_trajopt/function/smooth_function.h"

namespace fesd {

/// First- and second-order forward-mode scalars (Eigen's AutoDiff module).
using FirstOrder = Eigen::AutoDiffScalar<Eigen::VectorXd>;
using SecondOrder = Eigen::AutoDiffScalar<Eigen::Matrix<FirstOrder, Eigen::Dynamic, 1>>;

/// A SmoothFunction from a functor templated on the scalar type:
///   template <class T> void operator()(const T* z, T* y) const;
/// Jacobians by forward mode, Hessians of w^T F by forward-over-forward mode: exact to rounding.
/// The model-level blocks are dense (the functor is a black box, so no structural zero can be
/// proven); the NLP built from them stays sparse because each block only touches its own point.
/// The functor is shared between the threads that evaluate the NLP: it must keep no state
/// between calls (SmoothFunction::threadCopy).
template <class Functor>
class AutoDiffFunction : public SmoothFunction {
 public:
  AutoDiffFunction(int input_size, int output_size, Functor functor)
      : input_size_(input_size),
        output_size_(output_size),
        functor_(std::move(functor)),
        jacobian_pattern_(SparsityPattern::dense(output_size, input_size)),
        hessian_pattern_(SparsityPattern::dense(input_size, input_size, true)) {}

  int inputSize() const override { return input_size_; }
  int outputSize() const override { return output_size_; }
  void evaluate(const double* z, double* y) const override { functor_(z, y); }
  const SparsityPattern& jacobianPattern() const override { return jacobian_pattern_; }
  const SparsityPattern& hessianPattern() const override { return hessian_pattern_; }

  void evaluateJacobian(const double* z, double* values) const override {
    std::vector<FirstOrder> zz(input_size_), yy(output_size_);
    for (int i = 0; i < input_size_; ++i) zz[i] = FirstOrder(z[i], input_size_, i);
    functor_(zz.data(), yy.data());
    int k = 0;
    for (int r = 0; r < output_size_; ++r) {
      for (int c = 0; c < input_size_; ++c) {
        values[k++] = yy[r].derivatives().size() ? yy[r].derivatives()(c) : 0.0;
      }
    }
  }

  void evaluateHessian(const double* z, const double* weights, double* values) const override {
    const int n = input_size_;
    std::vector<SecondOrder> zz(n), yy(output_size_);
    for (int i = 0; i < n; ++i) {
      zz[i].value() = FirstOrder(z[i], n, i);
      zz[i].derivatives() = Eigen::Matrix<FirstOrder, Eigen::Dynamic, 1>::Unit(n, i);
    }
    functor_(zz.data(), yy.data());
    Eigen::MatrixXd hessian = Eigen::MatrixXd::Zero(n, n);
    for (int r = 0; r < output_size_; ++r) {
      const auto& gradient = yy[r].derivatives();
      for (int i = 0; i < gradient.size(); ++i) {
        const Eigen::VectorXd& row = gradient(i).derivatives();
        if (row.size()) hessian.row(i) += weights[r] * row.transpose();
      }
    }
    int k = 0;
    for (int r = 0; r < n; ++r) {
      for (int c = 0; c <= r; ++c) values[k++] = hessian(r, c);
    }
  }

 private:
  int input_size_, output_size_;
  Functor functor_;
  SparsityPattern jacobian_pattern_, hessian_pattern_;
};

template <class Functor>
std::shared_ptr<const SmoothFunction> makeAutoDiffFunction(int input_size, int output_size,
                                                           Functor functor) {
  return std::make_shared<AutoDiffFunction<Functor>>(input_size, output_size, std::move(functor));
}

}  // namespace fesd
