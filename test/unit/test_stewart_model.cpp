// Stewart's reformulation of Filippov systems (Nurkanovic et al. 2024, Sec. 2.2-2.3;
// model/stewart_model.cpp): the sign matrix and the model functions, against finite differences
// and closed forms.
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/filippov_examples.h"
#include "fesd_trajopt/model/stewart_model.h"
#include "support/finite_differences.h"

namespace {

using fesd_test::checkAgainstFiniteDifferences;
using fesd_test::kTolerance;
using fesd_test::randomVector;

TEST(SignMatrix, RowsAreAllSignPatternsInOrder) {
  const Eigen::MatrixXd s = fesd::signMatrix(2);
  Eigen::MatrixXd expected(4, 2);
  expected << 1, 1, 1, -1, -1, 1, -1, -1;
  EXPECT_EQ(s, expected);
  EXPECT_THROW(fesd::signMatrix(0), std::invalid_argument);
}

/// Proposition 2: in the region with the signs of row i, g = -S c is smallest in component i.
TEST(SignMatrix, IndicatorOfTheRegionIsTheSmallest) {
  std::mt19937 random(2);
  const Eigen::MatrixXd s = fesd::signMatrix(3);
  for (int trial = 0; trial < 50; ++trial) {
    const Eigen::VectorXd c = randomVector(3, random);
    const Eigen::VectorXd g = -s * c;
    int region = 0;
    for (int j = 0; j < 3; ++j) region = 2 * region + (c(j) < 0.0 ? 1 : 0);
    Eigen::Index smallest;
    g.minCoeff(&smallest);
    EXPECT_EQ(smallest, region);
  }
}

/// A nonlinear system with a user-given g: two subsystems with 3 and 2 modes, x in R^3, u in
/// R^2, so that the velocity's Hessian mixes x, u and theta.
struct NonlinearModes {
  template <class T>
  void operator()(const T* x, const T* u, T* F) const {
    using std::cos;
    using std::sin;
    for (int i = 0; i < 5; ++i) {
      F[3 * i] = sin(x[0] * (i + 1)) + u[0] * x[1];
      F[3 * i + 1] = x[2] * x[2] * u[1] - 0.5 * i;
      F[3 * i + 2] = cos(x[1]) * x[0] + u[0] * u[1] * i;
    }
  }
};
struct NonlinearIndicators {
  template <class T>
  void operator()(const T* x, T* g) const {
    using std::exp;
    g[0] = x[0] * x[1];
    g[1] = exp(0.3 * x[2]) - x[0];
    g[2] = x[1] * x[1] * x[2];
    g[3] = x[0] + x[2] * x[2] * x[2];
    g[4] = -x[1];
  }
};

TEST(StewartModelFunctions, DerivativesAgainstFiniteDifferences) {
  std::mt19937 random(9);
  const auto user_g =
      fesd::makeStewartModel(3, 2, {3, 2}, NonlinearModes{}, NonlinearIndicators{}, "nonlinear");
  const auto switching = fesd::sliding_ocp_example::model();
  for (const auto& model : {user_g, switching}) {
    const int nz = model->velocity()->inputSize();
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::VectorXd z = randomVector(nz, random, -2.0, 2.0);
      const auto velocity = checkAgainstFiniteDifferences(*model->velocity(), z,
                                                          randomVector(model->stateSize(), random));
      EXPECT_LT(velocity.jacobian, kTolerance) << model->name();
      EXPECT_LT(velocity.hessian, kTolerance) << model->name();
      const auto indicators =
          checkAgainstFiniteDifferences(*model->indicators(), z.head(model->stateSize()),
                                        randomVector(model->numModes(), random));
      EXPECT_LT(indicators.jacobian, kTolerance) << model->name();
      EXPECT_LT(indicators.hessian, kTolerance) << model->name();
    }
  }
}

/// OCP (61)'s model: v = sum_k F^k theta^k with qdot_k = v_k -/+ 1 in mode 0/1 of subsystem k,
/// and g^k = (-phi_k, phi_k) from S = [1; -1].
TEST(StewartModelFunctions, CartesianProductVelocityAndSignedIndicators) {
  const auto model = fesd::sliding_ocp_example::model();
  ASSERT_EQ(model->numSubsystems(), 2);
  ASSERT_EQ(model->numModes(), 4);
  EXPECT_EQ(model->subsystemOf(1), 0);
  EXPECT_EQ(model->subsystemOf(2), 1);
  std::mt19937 random(4);
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd x = randomVector(4, random, -2.0, 2.0);
    const Eigen::VectorXd u = randomVector(2, random);
    Eigen::VectorXd theta = randomVector(4, random, 0.0, 1.0);
    theta.head(2) /= theta.head(2).sum();
    theta.tail(2) /= theta.tail(2).sum();
    Eigen::VectorXd z(10), v(4), g(4);
    z << x, u, theta;
    model->velocity()->evaluate(z.data(), v.data());
    EXPECT_NEAR(v(0), x(2) - theta(0) + theta(1), 1e-14);
    EXPECT_NEAR(v(1), x(3) - theta(2) + theta(3), 1e-14);
    EXPECT_NEAR(v(2), u(0), 1e-14);
    EXPECT_NEAR(v(3), u(1), 1e-14);
    model->indicators()->evaluate(x.data(), g.data());
    const double phi1 = x(0) + 0.15 * x(1) * x(1), phi2 = -0.05 * std::pow(x(0), 3) + x(1);
    EXPECT_NEAR(g(0), -phi1, 1e-14);
    EXPECT_NEAR(g(1), phi1, 1e-14);
    EXPECT_NEAR(g(2), -phi2, 1e-14);
    EXPECT_NEAR(g(3), phi2, 1e-14);
    // The LP multipliers: mu^k = min g^k, lambda = g - mu^k e, zero at the active mode.
    Eigen::VectorXd lambda(4), mu(2);
    model->lpMultipliers(x.data(), lambda.data(), mu.data());
    EXPECT_NEAR(mu(0), -std::fabs(phi1), 1e-14);
    EXPECT_NEAR(mu(1), -std::fabs(phi2), 1e-14);
    EXPECT_DOUBLE_EQ(lambda(phi1 > 0 ? 0 : 1), 0.0);
    EXPECT_NEAR(lambda(phi1 > 0 ? 1 : 0), 2.0 * std::fabs(phi1), 1e-14);
  }
}

}  // namespace
