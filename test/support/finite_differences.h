#pragma once

#include <functional>
#include <random>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/function/smooth_function.h"
#include "fesd_trajopt/nlp/nlp_problem.h"

namespace fesd_test {

/// The bound of the derivative tests on the relative errors below (Jacobians and Hessians).
constexpr double kTolerance = 1e-6;

/// Dense matrix from a sparsity pattern and its values; `symmetric` mirrors a lower triangle.
Eigen::MatrixXd densify(const fesd::SparsityPattern& pattern, const std::vector<double>& values,
                        int rows, int cols, bool symmetric = false);

/// Central-difference Jacobian of a vector function.
Eigen::MatrixXd finiteDifferenceJacobian(
    const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& function,
    const Eigen::VectorXd& at, double step = 1e-6);

/// The exact Jacobian and weighted Hessian of a SmoothFunction.
Eigen::MatrixXd exactJacobian(const fesd::SmoothFunction& function, const Eigen::VectorXd& z);
Eigen::MatrixXd exactHessian(const fesd::SmoothFunction& function, const Eigen::VectorXd& z,
                             const Eigen::VectorXd& weights);

/// Largest error of the Jacobian and of the weighted Hessian of a SmoothFunction against
/// central differences (of the values and of the weighted gradient), relative to max(1, |entry|).
struct DerivativeErrors {
  double jacobian, hessian;
};
DerivativeErrors checkAgainstFiniteDifferences(const fesd::SmoothFunction& function,
                                               const Eigen::VectorXd& z,
                                               const Eigen::VectorXd& weights);

/// The same for a whole NLP: constraint Jacobian and Hessian of the Lagrangian.
DerivativeErrors checkNlpAgainstFiniteDifferences(const fesd::NlpProblem& nlp,
                                                  const Eigen::VectorXd& x, double objective_factor,
                                                  const Eigen::VectorXd& multipliers);

Eigen::VectorXd randomVector(int size, std::mt19937& random, double low = -1.0, double high = 1.0);

/// The worst errors of checkNlpAgainstFiniteDifferences over `trials` random relaxations,
/// points with every variable in [0.05, 1] (inside any complementarity's domain) and
/// multipliers.
DerivativeErrors checkRelaxedNlpAtRandomPoints(fesd::RelaxedMpcc& nlp, int trials, unsigned seed);

}  // namespace fesd_test
