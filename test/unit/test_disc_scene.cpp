// Disc scenes' contact model (scene/disc_scene.cpp): velocity and constraint derivatives against
// central finite differences in 2-D and 3-D, and the constraint values pair by pair.
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/scene/disc_scene.h"
#include "support/finite_differences.h"

namespace {

using fesd_test::checkAgainstFiniteDifferences;
using fesd_test::kTolerance;
using fesd_test::randomVector;

/// A scene with every kind of contact pair: bodies (actuated and passive), an obstacle, walls.
fesd::DiscScene mixedScene(int dimension, std::mt19937& random) {
  fesd::DiscScene scene(dimension);
  for (int b = 0; b < 4; ++b) {
    scene.bodies().push_back({"body" + std::to_string(b), 0.5 + 0.2 * b,
                              randomVector(dimension, random, -3.0, 3.0), b % 2 == 0});
  }
  scene.obstacles().push_back({"post", 0.7, randomVector(dimension, random, -3.0, 3.0)});
  Eigen::VectorXd normal = randomVector(dimension, random);
  scene.walls().push_back({"slanted", normal.normalized(), -4.0});
  Eigen::VectorXd axis = Eigen::VectorXd::Zero(dimension);
  axis(1) = 1.0;
  scene.walls().push_back({"floor", axis, -5.0});  // a normal with zero components
  return scene;
}

class SceneDerivatives : public ::testing::TestWithParam<int> {};

TEST_P(SceneDerivatives, VelocityAndConstraintsAgainstFiniteDifferences) {
  std::mt19937 random(23);
  const fesd::DiscScene scene = mixedScene(GetParam(), random);
  const auto pairs = scene.allPairs();
  const auto model = scene.model(pairs);
  EXPECT_EQ(model->constraintSize(), 6 + 4 + 8);  // 6 body pairs, 4 obstacle, 8 wall pairs
  EXPECT_EQ(model->controlSize(), 2 * GetParam());
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd z = randomVector(model->velocity()->inputSize(), random, -3.0, 3.0);
    const auto velocity = checkAgainstFiniteDifferences(*model->velocity(), z,
                                                        randomVector(scene.stateSize(), random));
    EXPECT_LT(velocity.jacobian, kTolerance);
    EXPECT_LT(velocity.hessian, kTolerance);
    const Eigen::VectorXd x = z.head(scene.stateSize());
    const auto constraints = checkAgainstFiniteDifferences(
        *model->constraints(), x, randomVector(model->constraintSize(), random));
    EXPECT_LT(constraints.jacobian, kTolerance);
    EXPECT_LT(constraints.hessian, kTolerance);
    // The constraint values are the geometric ones, pair by pair.
    Eigen::VectorXd c(model->constraintSize());
    model->constraints()->evaluate(x.data(), c.data());
    for (size_t k = 0; k < pairs.size(); ++k) {
      EXPECT_DOUBLE_EQ(c(k), scene.constraintValue(pairs[k], x)) << scene.pairName(pairs[k]);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(PlanarAndSpatial, SceneDerivatives, ::testing::Values(2, 3));

}  // namespace
