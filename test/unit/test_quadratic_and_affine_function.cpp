// QuadraticFunction and AffineFunction (function/quadratic_function.cpp, affine_function.cpp):
// Jacobians and Hessians against central finite differences, and a weighted distance's value.
#include <random>

#include <gtest/gtest.h>

#include "fesd_trajopt/function/affine_function.h"
#include "fesd_trajopt/function/quadratic_function.h"
#include "support/finite_differences.h"

namespace {

using fesd_test::checkAgainstFiniteDifferences;
using fesd_test::kTolerance;
using fesd_test::randomVector;

TEST(ModelDerivatives, QuadraticAndAffineFunctions) {
  std::mt19937 random(5);
  Eigen::SparseMatrix<double> q(3, 3);
  q.insert(0, 0) = 2.0;
  q.insert(1, 2) = -0.5;
  q.insert(2, 1) = -0.5;
  q.insert(2, 2) = 1.0;
  const fesd::QuadraticFunction quadratic(q, Eigen::Vector3d(0.0, 1.0, -2.0), 3.0);
  Eigen::SparseMatrix<double> a(2, 3);
  a.insert(0, 1) = 4.0;
  a.insert(1, 0) = -1.0;
  a.insert(1, 2) = 0.5;
  const fesd::AffineFunction affine(a, Eigen::Vector2d(1.0, -1.0));
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd z = randomVector(3, random, -2.0, 2.0);
    const auto qe = checkAgainstFiniteDifferences(quadratic, z, randomVector(1, random));
    EXPECT_LT(qe.jacobian, kTolerance);
    EXPECT_LT(qe.hessian, kTolerance);
    const auto ae = checkAgainstFiniteDifferences(affine, z, randomVector(2, random));
    EXPECT_LT(ae.jacobian, kTolerance);
    EXPECT_LT(ae.hessian, kTolerance);
  }
  const auto distance = fesd::QuadraticFunction::weightedDistance(Eigen::Vector2d(2.0, 0.5),
                                                                  Eigen::Vector2d(1.0, -1.0));
  double value;
  const Eigen::Vector2d at(3.0, 1.0);
  distance->evaluate(at.data(), &value);
  EXPECT_DOUBLE_EQ(value, 2.0 * 4.0 + 0.5 * 4.0);
}

}  // namespace
