// The analytic model of Example 1 (examples/circle_example.cpp): velocity and constraint
// derivatives against central finite differences and against its AutoDiff twin.
#include <random>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/circle_example.h"
#include "support/finite_differences.h"

namespace {

using fesd_test::checkAgainstFiniteDifferences;
using fesd_test::kTolerance;
using fesd_test::randomVector;

TEST(ModelDerivatives, AnalyticCircleExampleMatchesFiniteDifferencesAndAutoDiff) {
  std::mt19937 random(11);
  const auto analytic = fesd::circle_example::model();
  const auto autodiff = fesd::circle_example::autodiffModel();
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd z = randomVector(3, random, -3.0, 3.0);
    const auto errors =
        checkAgainstFiniteDifferences(*analytic->velocity(), z, randomVector(2, random));
    EXPECT_LT(errors.jacobian, kTolerance);
    EXPECT_LT(errors.hessian, kTolerance);
    const auto c_errors =
        checkAgainstFiniteDifferences(*analytic->constraints(), z.head(2), randomVector(1, random));
    EXPECT_LT(c_errors.jacobian, kTolerance);
    EXPECT_LT(c_errors.hessian, kTolerance);
    EXPECT_LT((fesd_test::exactJacobian(*analytic->velocity(), z) -
               fesd_test::exactJacobian(*autodiff->velocity(), z))
                  .norm(),
              1e-14);
  }
}

}  // namespace
