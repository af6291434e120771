// Pair gaps (scene/pair_check.cpp): signed gaps of body, obstacle and wall pairs, and the
// smallest gap along a path, exact for straight motion between samples.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/scene/pair_check.h"

namespace {

/// A disc (R = 0.5) and a thin one (R = 0.05), a post (R = 1) at (0, 3), a floor y >= -2.
fesd::DiscScene scene() {
  fesd::DiscScene scene(2);
  scene.bodies() = {{"disc", 0.5, Eigen::Vector2d(-3.0, 0.0), true},
                    {"thin", 0.05, Eigen::Vector2d(0.0, 0.0), false}};
  scene.obstacles() = {{"post", 1.0, Eigen::Vector2d(0.0, 3.0)}};
  scene.walls() = {{"floor", Eigen::Vector2d(0.0, 1.0), -2.0}};
  return scene;
}

Eigen::VectorXd state(double disc_x, double disc_y) {
  Eigen::VectorXd x(4);
  x << disc_x, disc_y, 0.0, 0.0;
  return x;
}

const fesd::ContactPair kDiscThin{0, fesd::ContactPair::Kind::kBody, 1};
const fesd::ContactPair kDiscPost{0, fesd::ContactPair::Kind::kObstacle, 0};
const fesd::ContactPair kDiscFloor{0, fesd::ContactPair::Kind::kWall, 0};

TEST(PairCheck, GapsAndSizesOfBodyObstacleAndWallPairs) {
  const fesd::DiscScene s = scene();
  EXPECT_DOUBLE_EQ(fesd::pairSize(s, kDiscThin), 0.55);
  EXPECT_DOUBLE_EQ(fesd::pairSize(s, kDiscPost), 1.5);
  EXPECT_DOUBLE_EQ(fesd::pairSize(s, kDiscFloor), 0.5);
  EXPECT_NEAR(fesd::pairGap(s, kDiscThin, state(-3.0, 0.0)), 3.0 - 0.55, 1e-15);
  EXPECT_NEAR(fesd::pairGap(s, kDiscThin, state(0.0, 0.3)), 0.3 - 0.55, 1e-15);  // overlap
  EXPECT_NEAR(fesd::pairGap(s, kDiscPost, state(3.0, 3.0)), 1.5, 1e-15);
  EXPECT_NEAR(fesd::pairGap(s, kDiscFloor, state(7.0, -1.0)), 0.5, 1e-15);
}

TEST(PairCheck, AThinBodyBetweenTwoSamplesIsNotJumpedOver) {
  const fesd::DiscScene s = scene();
  // Two samples 1.2 either side of the thin disc: both ends are 0.65 clear, the segment passes
  // straight through it.
  const std::vector<Eigen::VectorXd> path{state(-1.2, 0.1), state(1.2, 0.1)};
  EXPECT_GT(fesd::pairGap(s, kDiscThin, path.front()), 0.6);
  EXPECT_GT(fesd::pairGap(s, kDiscThin, path.back()), 0.6);
  EXPECT_NEAR(fesd::smallestGap(s, kDiscThin, path), 0.1 - 0.55, 1e-15);
  // Past the post on a tangent line: the closest approach is the gap at its foot, 2 - 1.5.
  EXPECT_NEAR(fesd::smallestGap(s, kDiscPost, {state(-4.0, 1.0), state(4.0, 1.0)}), 0.5, 1e-15);
  // Walls are linear in the position: the ends bound the segment.
  EXPECT_NEAR(fesd::smallestGap(s, kDiscFloor, {state(0.0, 1.0), state(5.0, -1.2), state(9, 0)}),
              0.8 - 0.5, 1e-15);
  EXPECT_EQ(fesd::smallestGap(s, kDiscThin, {}), std::numeric_limits<double>::infinity());
}

}  // namespace
