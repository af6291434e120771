#include "support/finite_differences.h"

#include <algorithm>

namespace fesd_test {

Eigen::MatrixXd densify(const fesd::SparsityPattern& pattern, const std::vector<double>& values,
                        int rows, int cols, bool symmetric) {
  Eigen::MatrixXd dense = Eigen::MatrixXd::Zero(rows, cols);
  for (int e = 0; e < pattern.nonzeros(); ++e) {
    dense(pattern.rows[e], pattern.cols[e]) += values[e];
    if (symmetric && pattern.rows[e] != pattern.cols[e]) {
      dense(pattern.cols[e], pattern.rows[e]) += values[e];
    }
  }
  return dense;
}

Eigen::MatrixXd finiteDifferenceJacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& function,
    const Eigen::VectorXd& at, double step) {
  const Eigen::VectorXd center = function(at);
  Eigen::MatrixXd jacobian(center.size(), at.size());
  for (int i = 0; i < at.size(); ++i) {
    Eigen::VectorXd plus = at, minus = at;
    const double h = step * std::max(1.0, std::abs(at(i)));
    plus(i) += h;
    minus(i) -= h;
    jacobian.col(i) = (function(plus) - function(minus)) / (2.0 * h);
  }
  return jacobian;
}

Eigen::MatrixXd exactJacobian(const fesd::SmoothFunction& function, const Eigen::VectorXd& z) {
  std::vector<double> values(function.jacobianPattern().nonzeros());
  function.evaluateJacobian(z.data(), values.data());
  return densify(function.jacobianPattern(), values, function.outputSize(), function.inputSize());
}

Eigen::MatrixXd exactHessian(const fesd::SmoothFunction& function, const Eigen::VectorXd& z,
                             const Eigen::VectorXd& weights) {
  std::vector<double> values(function.hessianPattern().nonzeros());
  function.evaluateHessian(z.data(), weights.data(), values.data());
  return densify(function.hessianPattern(), values, function.inputSize(), function.inputSize(),
                 true);
}

namespace {
/// Largest |exact - approximate| relative to max(1, |exact|, 1e-3 |row magnitude|): central
/// differences of a row whose values reach |g| carry a rounding error of about eps |g| / step,
/// i.e. 2e-10 |g| at our step, so large rows (the big-M bounds) get a proportionate allowance.
double relativeError(const Eigen::MatrixXd& exact, const Eigen::MatrixXd& approximate,
                     const Eigen::VectorXd& row_magnitude = Eigen::VectorXd()) {
  double worst = 0.0;
  for (int r = 0; r < exact.rows(); ++r) {
    const double row_scale = row_magnitude.size() ? 1e-3 * row_magnitude(r) : 0.0;
    for (int c = 0; c < exact.cols(); ++c) {
      worst = std::max(worst, std::abs(exact(r, c) - approximate(r, c)) /
                                  std::max({1.0, std::abs(exact(r, c)), row_scale}));
    }
  }
  return worst;
}
}  // namespace

DerivativeErrors checkAgainstFiniteDifferences(const fesd::SmoothFunction& function,
                                               const Eigen::VectorXd& z,
                                               const Eigen::VectorXd& weights) {
  auto value = [&](const Eigen::VectorXd& at) {
    Eigen::VectorXd y(function.outputSize());
    function.evaluate(at.data(), y.data());
    return y;
  };
  auto weighted_gradient = [&](const Eigen::VectorXd& at) -> Eigen::VectorXd {
    return exactJacobian(function, at).transpose() * weights;
  };
  return {relativeError(exactJacobian(function, z), finiteDifferenceJacobian(value, z)),
          relativeError(exactHessian(function, z, weights),
                        finiteDifferenceJacobian(weighted_gradient, z))};
}

DerivativeErrors checkNlpAgainstFiniteDifferences(const fesd::NlpProblem& nlp,
                                                  const Eigen::VectorXd& x, double objective_factor,
                                                  const Eigen::VectorXd& multipliers) {
  const int n = nlp.numVariables(), m = nlp.numConstraints();
  auto constraints = [&](const Eigen::VectorXd& at) {
    Eigen::VectorXd g(m);
    nlp.constraints(at.data(), g.data());
    return g;
  };
  auto jacobian = [&](const Eigen::VectorXd& at) {
    std::vector<double> values(nlp.jacobianPattern().nonzeros());
    nlp.jacobian(at.data(), values.data());
    return densify(nlp.jacobianPattern(), values, m, n);
  };
  auto lagrangian_gradient = [&](const Eigen::VectorXd& at) -> Eigen::VectorXd {
    Eigen::VectorXd gradient(n);
    nlp.objectiveGradient(at.data(), gradient.data());
    return objective_factor * gradient + jacobian(at).transpose() * multipliers;
  };
  auto objective = [&](const Eigen::VectorXd& at) {
    return Eigen::VectorXd::Constant(1, nlp.objective(at.data()));
  };
  std::vector<double> hessian_values(nlp.hessianPattern().nonzeros());
  nlp.hessian(x.data(), objective_factor, multipliers.data(), hessian_values.data());
  const Eigen::MatrixXd hessian = densify(nlp.hessianPattern(), hessian_values, n, n, true);
  Eigen::VectorXd gradient(n);
  nlp.objectiveGradient(x.data(), gradient.data());
  const double gradient_error =
      relativeError(gradient.transpose(), finiteDifferenceJacobian(objective, x));
  // The Hessian's rows are differences of Lagrangian gradients, whose size follows the
  // multiplier-weighted Jacobian columns.
  const Eigen::VectorXd constraint_magnitude = constraints(x).cwiseAbs();
  const Eigen::VectorXd gradient_magnitude =
      (jacobian(x).cwiseAbs().transpose() * multipliers.cwiseAbs()).cwiseMax(gradient.cwiseAbs());
  return {
      std::max(gradient_error, relativeError(jacobian(x), finiteDifferenceJacobian(constraints, x),
                                             constraint_magnitude)),
      relativeError(hessian, finiteDifferenceJacobian(lagrangian_gradient, x), gradient_magnitude)};
}

Eigen::VectorXd randomVector(int size, std::mt19937& random, double low, double high) {
  std::uniform_real_distribution<double> uniform(low, high);
  Eigen::VectorXd v(size);
  for (int i = 0; i < size; ++i) v(i) = uniform(random);
  return v;
}

DerivativeErrors checkRelaxedNlpAtRandomPoints(fesd::RelaxedMpcc& nlp, int trials, unsigned seed) {
  std::mt19937 random(seed);
  DerivativeErrors worst{0.0, 0.0};
  for (int trial = 0; trial < trials; ++trial) {
    nlp.setRelaxation(std::uniform_real_distribution<double>(0.0, 1.0)(random));
    const Eigen::VectorXd x = randomVector(nlp.numVariables(), random, 0.05, 1.0);
    const Eigen::VectorXd multipliers = randomVector(nlp.numConstraints(), random);
    const DerivativeErrors errors = checkNlpAgainstFiniteDifferences(nlp, x, 0.7, multipliers);
    worst.jacobian = std::max(worst.jacobian, errors.jacobian);
    worst.hessian = std::max(worst.hessian, errors.hessian);
  }
  return worst;
}

}  // namespace fesd_test
