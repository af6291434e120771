#include "fesd_trajopt/discretization/step_equilibration_residual.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fesd {
namespace {

std::vector<int> occurrences(const std::vector<int>& positions, int num_blocks) {
  std::vector<int> count(num_blocks, 0);
  for (int p : positions) ++count[p];
  return count;
}

int numBlocks(const SwitchIndicator& indicator) {
  int largest = -1;
  for (const std::vector<int>* sum : {&indicator.lambda_backward, &indicator.lambda_forward,
                                      &indicator.theta_backward, &indicator.theta_forward}) {
    if (sum->empty()) throw std::invalid_argument("SwitchIndicator: a sum without blocks");
    largest = std::max(largest, *std::max_element(sum->begin(), sum->end()));
  }
  return largest + 1;
}

}  // namespace

StepEquilibrationResidual::StepEquilibrationResidual(SwitchIndicator indicator, double nominal_step,
                                                     bool tanh_scaled)
    : indicator_(std::move(indicator)),
      num_blocks_(numBlocks(indicator_)),
      nominal_step_(nominal_step),
      tanh_scaled_(tanh_scaled),
      in_lambda_backward_(occurrences(indicator_.lambda_backward, num_blocks_)),
      in_lambda_forward_(occurrences(indicator_.lambda_forward, num_blocks_)),
      in_theta_backward_(occurrences(indicator_.theta_backward, num_blocks_)),
      in_theta_forward_(occurrences(indicator_.theta_forward, num_blocks_)),
      jacobian_pattern_(SparsityPattern::dense(1, inputSize())) {
  // Both steps enter linearly and only through their difference: no (step, step) entries.
  for (int row = 2; row < inputSize(); ++row) {
    for (int col = 0; col <= row; ++col) hessian_pattern_.add(row, col);
  }
}

StepEquilibrationResidual::Factors StepEquilibrationResidual::factors(const double* blocks) const {
  const int nf = indicator_.nf;
  Factors at;
  for (int mode = 0; mode < nf; ++mode) {
    at.lambda_backward.push_back(indicator_.sum(blocks, indicator_.lambda_backward, mode));
    at.lambda_forward.push_back(indicator_.sum(blocks, indicator_.lambda_forward, mode));
    at.theta_backward.push_back(indicator_.sum(blocks, indicator_.theta_backward, mode));
    at.theta_forward.push_back(indicator_.sum(blocks, indicator_.theta_forward, mode));
    at.factor.push_back(at.lambda_backward[mode] * at.lambda_forward[mode] +
                        at.theta_backward[mode] * at.theta_forward[mode]);
  }
  at.eta = at.factor[0];
  for (int mode = 1; mode < nf; ++mode) at.eta *= at.factor[mode];
  return at;
}

double StepEquilibrationResidual::factorSlope(const Factors& at, int position, int mode) const {
  return in_lambda_backward_[position] * at.lambda_forward[mode] +
         in_lambda_forward_[position] * at.lambda_backward[mode] +
         in_theta_backward_[position] * at.theta_forward[mode] +
         in_theta_forward_[position] * at.theta_backward[mode];
}

double StepEquilibrationResidual::factorCurvature(int position, int other) const {
  return in_lambda_backward_[position] * in_lambda_forward_[other] +
         in_lambda_forward_[position] * in_lambda_backward_[other] +
         in_theta_backward_[position] * in_theta_forward_[other] +
         in_theta_forward_[position] * in_theta_backward_[other];
}

double StepEquilibrationResidual::productWithout(const std::vector<double>& factor, int skip,
                                                 int also_skip) {
  double product = 1.0;
  for (int mode = 0; mode < static_cast<int>(factor.size()); ++mode) {
    if (mode != skip && mode != also_skip) product *= factor[mode];
  }
  return product;
}

void StepEquilibrationResidual::scaling(double eta, double* g, double* slope,
                                        double* curvature) const {
  if (!tanh_scaled_) {
    *g = eta, *slope = 1.0, *curvature = 0.0;
    return;
  }
  // tanh(eta) for eta >= 0 (sums of nonnegative variables), by exp alone.
  const double decay = std::exp(-2.0 * eta);
  *g = (1.0 - decay) / (1.0 + decay);
  *slope = 4.0 * decay / ((1.0 + decay) * (1.0 + decay));
  *curvature = -2.0 * *g * *slope;
}

void StepEquilibrationResidual::evaluate(const double* z, double* y) const {
  double g, slope, curvature;
  scaling(indicator_(z + 2), &g, &slope, &curvature);
  y[0] = (z[1] - z[0]) * (1.0 / nominal_step_) * g;
}

void StepEquilibrationResidual::evaluateJacobian(const double* z, double* values) const {
  const int nf = indicator_.nf;
  const Factors at = factors(z + 2);
  double g, slope, curvature;
  scaling(at.eta, &g, &slope, &curvature);
  const double inverse_step = 1.0 / nominal_step_;
  values[0] = -inverse_step * g;
  values[1] = inverse_step * g;
  const double outer = (z[1] - z[0]) * inverse_step * slope;
  for (int mode = 0; mode < nf; ++mode) {
    const double others = productWithout(at.factor, mode, -1);
    for (int p = 0; p < num_blocks_; ++p) {
      values[2 + p * nf + mode] = outer * others * factorSlope(at, p, mode);
    }
  }
}

void StepEquilibrationResidual::evaluateHessian(const double* z, const double* weights,
                                                double* values) const {
  const int nf = indicator_.nf;
  const int num_blocks_inputs = num_blocks_ * nf;
  const Factors at = factors(z + 2);
  double g, slope, curvature;
  scaling(at.eta, &g, &slope, &curvature);
  const double scale = weights[0] / nominal_step_;
  const double difference = z[1] - z[0];
  // The indicator's gradient, by block input.
  std::vector<double> gradient(num_blocks_inputs);
  std::vector<double> others(nf);
  for (int mode = 0; mode < nf; ++mode) {
    others[mode] = productWithout(at.factor, mode, -1);
    for (int p = 0; p < num_blocks_; ++p) {
      gradient[p * nf + mode] = others[mode] * factorSlope(at, p, mode);
    }
  }
  int k = 0;
  for (int b = 0; b < num_blocks_inputs; ++b) {
    const int p = b / nf, mode = b % nf;
    values[k++] = -scale * slope * gradient[b];
    values[k++] = scale * slope * gradient[b];
    for (int c = 0; c <= b; ++c) {
      const int q = c / nf, other_mode = c % nf;
      const double indicator_curvature =
          mode == other_mode ? others[mode] * factorCurvature(p, q)
                             : productWithout(at.factor, mode, other_mode) *
                                   factorSlope(at, p, mode) * factorSlope(at, q, other_mode);
      values[k++] = scale * difference *
                    (curvature * gradient[b] * gradient[c] + slope * indicator_curvature);
    }
  }
}

}  // namespace fesd
