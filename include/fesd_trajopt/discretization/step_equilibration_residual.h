#pragma once

#include <cstddef>
#include <vector>

#include "fesd_trajopt/function/smooth_function.h"

namespace fesd {

/// The switch indicator of step equilibration (Nurkanovic et al. 2024, eq. 31) at the boundary
/// between two elements, on blocks of n_f values (lambda or theta at a point):
///   eta = prod_i (sum_B lambda_i sum_F lambda_i + sum_B theta_i sum_F theta_i),
/// B over the earlier element's closure, F over the later one's. The sums list block positions;
/// the lambda block at the common boundary belongs to both.
struct SwitchIndicator {
  int nf;
  std::vector<int> lambda_backward, lambda_forward, theta_backward, theta_forward;

  template <class T>
  T sum(const T* blocks, const std::vector<int>& positions, int mode) const {
    T total = blocks[positions[0] * nf + mode];
    for (std::size_t p = 1; p < positions.size(); ++p) total += blocks[positions[p] * nf + mode];
    return total;
  }
  template <class T>
  T factor(const T* blocks, int mode) const {
    return sum(blocks, lambda_backward, mode) * sum(blocks, lambda_forward, mode) +
           sum(blocks, theta_backward, mode) * sum(blocks, theta_forward, mode);
  }
  template <class T>
  T operator()(const T* blocks) const {
    T eta = factor(blocks, 0);
    for (int i = 1; i < nf; ++i) eta *= factor(blocks, i);
    return eta;
  }
};

/// Step equilibration's residual ((h_n - h_{n-1}) / h0) g(eta) (Nurkanovic et al. 2024, eq. 31)
/// on z = (h_{n-1}, h_n, the indicator's blocks), g(eta) = eta or tanh(eta), with analytic
/// derivatives: eta is a product of n_f bilinear factors in sums of the blocks, so its Hessian
/// comes from the factors' partial products (automatic differentiation of a product over a few
/// dozen inputs spent most of a Filippov OCP's time allocating).
class StepEquilibrationResidual final : public SmoothFunction {
 public:
  StepEquilibrationResidual(SwitchIndicator indicator, double nominal_step, bool tanh_scaled);

  int inputSize() const override { return 2 + num_blocks_ * indicator_.nf; }
  int outputSize() const override { return 1; }
  void evaluate(const double* z, double* y) const override;
  const SparsityPattern& jacobianPattern() const override { return jacobian_pattern_; }
  void evaluateJacobian(const double* z, double* values) const override;
  const SparsityPattern& hessianPattern() const override { return hessian_pattern_; }
  void evaluateHessian(const double* z, const double* weights, double* values) const override;

 private:
  /// The indicator at the blocks with what its derivatives need.
  struct Factors {
    std::vector<double> lambda_backward, lambda_forward, theta_backward, theta_forward;  // sums
    std::vector<double> factor;                                                          // per mode
    double eta;
  };
  Factors factors(const double* blocks) const;
  /// d factor_mode / d blocks[position * nf + mode].
  double factorSlope(const Factors& at, int position, int mode) const;
  /// d^2 factor_mode / d blocks[position * nf + mode] d blocks[other * nf + mode].
  double factorCurvature(int position, int other) const;
  /// prod of the factors but those of modes `skip` and `also_skip` (-1: none).
  static double productWithout(const std::vector<double>& factor, int skip, int also_skip);
  /// g(eta), g'(eta), g''(eta).
  void scaling(double eta, double* g, double* slope, double* curvature) const;

  SwitchIndicator indicator_;
  int num_blocks_;
  double nominal_step_;
  bool tanh_scaled_;
  /// How often each block position occurs in each of the indicator's four sums.
  std::vector<int> in_lambda_backward_, in_lambda_forward_, in_theta_backward_, in_theta_forward_;
  SparsityPattern jacobian_pattern_, hessian_pattern_;
};

}  // namespace fesd
