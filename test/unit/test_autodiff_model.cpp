// AutoDiffModel (model/autodiff_model.h) on the nonlinear bead model: velocity and constraint
// derivatives against central finite differences, and the velocity f + grad c^T lambda.
#include <random>

#include <gtest/gtest.h>

#include "support/bead_model.h"
#include "support/finite_differences.h"

namespace {

using fesd_test::BeadConstraints;
using fesd_test::BeadDynamics;
using fesd_test::beadModel;
using fesd_test::checkAgainstFiniteDifferences;
using fesd_test::kTolerance;
using fesd_test::randomVector;

TEST(ModelDerivatives, AutoDiffModelAgainstFiniteDifferences) {
  std::mt19937 random(7);
  const auto model = beadModel();
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd z = randomVector(7, random);  // (x, u, lambda)
    const auto velocity =
        checkAgainstFiniteDifferences(*model->velocity(), z, randomVector(3, random));
    EXPECT_LT(velocity.jacobian, kTolerance);
    EXPECT_LT(velocity.hessian, kTolerance);
    const auto constraints =
        checkAgainstFiniteDifferences(*model->constraints(), z.head(3), randomVector(2, random));
    EXPECT_LT(constraints.jacobian, kTolerance);
    EXPECT_LT(constraints.hessian, kTolerance);
  }
}

TEST(ModelDerivatives, AutoDiffVelocityIsDynamicsPlusConstraintGradientTimesLambda) {
  std::mt19937 random(3);
  const auto model = beadModel();
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd z = randomVector(7, random);
    Eigen::VectorXd v(3), f(3);
    model->velocity()->evaluate(z.data(), v.data());
    BeadDynamics{}(z.data(), z.data() + 3, f.data());
    const Eigen::MatrixXd constraint_jacobian = fesd_test::finiteDifferenceJacobian(
        [](const Eigen::VectorXd& x) {
          Eigen::VectorXd c(2);
          BeadConstraints{}(x.data(), c.data());
          return c;
        },
        z.head(3));
    EXPECT_LT((v - f - constraint_jacobian.transpose() * z.tail(2)).norm(), 1e-8);
  }
}

}  // namespace
