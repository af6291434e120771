// Pair gaps (scene/pair_check.cpp): signed gaps of body, obstacle and wall pairs, the smallest
// gap along a path, exact for straight motion between samples, for free bodies and a robot's
// spheres, and the lazy pairs' margin.
#include <cmath>
#include <limits>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "fesd_trajopt/scene/pair_check.h"
#include "support/robot_files.h"

namespace {

/// A disc (R = 0.5) and a thin one (R = 0.05), a post (R = 1) at (0, 3), a floor y >= -2.
fesd::Scene scene() {
  fesd::Scene scene(2);
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
  const fesd::Scene s = scene();
  EXPECT_DOUBLE_EQ(s.pairSize(kDiscThin), 0.55);
  EXPECT_DOUBLE_EQ(s.pairSize(kDiscPost), 1.5);
  EXPECT_DOUBLE_EQ(s.pairSize(kDiscFloor), 0.5);
  EXPECT_NEAR(s.pairGap(kDiscThin, state(-3.0, 0.0)), 3.0 - 0.55, 1e-15);
  EXPECT_NEAR(s.pairGap(kDiscThin, state(0.0, 0.3)), 0.3 - 0.55, 1e-15);  // overlap
  EXPECT_NEAR(s.pairGap(kDiscPost, state(3.0, 3.0)), 1.5, 1e-15);
  EXPECT_NEAR(s.pairGap(kDiscFloor, state(7.0, -1.0)), 0.5, 1e-15);
}

TEST(PairCheck, AThinBodyBetweenTwoSamplesIsNotJumpedOver) {
  const fesd::Scene s = scene();
  // Two samples 1.2 either side of the thin disc: both ends are 0.65 clear, the segment passes
  // straight through it.
  const std::vector<Eigen::VectorXd> path{state(-1.2, 0.1), state(1.2, 0.1)};
  EXPECT_GT(s.pairGap(kDiscThin, path.front()), 0.6);
  EXPECT_GT(s.pairGap(kDiscThin, path.back()), 0.6);
  EXPECT_NEAR(fesd::smallestGap(s, kDiscThin, path), 0.1 - 0.55, 1e-15);
  // Past the post on a tangent line: the closest approach is the gap at its foot, 2 - 1.5.
  EXPECT_NEAR(fesd::smallestGap(s, kDiscPost, {state(-4.0, 1.0), state(4.0, 1.0)}), 0.5, 1e-15);
  // Walls are linear in the position: the ends bound the segment.
  EXPECT_NEAR(fesd::smallestGap(s, kDiscFloor, {state(0.0, 1.0), state(5.0, -1.2), state(9, 0)}),
              0.8 - 0.5, 1e-15);
  EXPECT_EQ(fesd::smallestGap(s, kDiscThin, {}), std::numeric_limits<double>::infinity());
}

}  // namespace

namespace {

fesd::SceneTask armPush() {
  return fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
}

fesd::ContactPair named(const fesd::SceneTask& task, const std::string& name) {
  for (const fesd::ContactPair& pair : task.scene.allPairs()) {
    if (task.scene.pairName(pair) == name) return pair;
  }
  ADD_FAILURE() << "no pair " << name;
  return {};
}

TEST(PairCheck, ARobotSpheresSizeAndGapAlongAPath) {
  const fesd::SceneTask task = armPush();
  const fesd::ContactPair hand = named(task, "disc/hand/sphere_0");
  EXPECT_DOUBLE_EQ(task.scene.pairSize(hand), 0.05 + 0.035);
  // At q = 0 the arm lies along x with hand/sphere_0 at (0.75, 0), 0.15 from the disc's centre
  // at (0.6, 0); at q0 it is farther.
  Eigen::VectorXd along_x = task.scene.initialState();
  along_x.head(3).setZero();
  EXPECT_NEAR(fesd::smallestGap(task.scene, hand, {along_x}), 0.15 - 0.085, 1e-12);
  // Between two states the sphere's centre is taken to move straight: the chord's distance.
  fesd::KinematicData data;
  fesd::forwardKinematics(task.scene.robot(), task.scene.initialJoints(), data);
  const int sphere = task.scene.collisionBodies()[hand.other].sphere;
  const Eigen::VectorXd from = data.sphere_centres[sphere].head(2);
  const Eigen::VectorXd to = Eigen::Vector2d(0.75, 0.0);
  const double chord = fesd::segmentDistance(Eigen::Vector2d(0.6, 0.0), from, to) - 0.085;
  EXPECT_LT(chord, 0.15 - 0.085);
  EXPECT_NEAR(fesd::smallestGap(task.scene, hand, {task.scene.initialState(), along_x}), chord,
              1e-12);
  EXPECT_NEAR(fesd::smallestGapsAt(task.scene, {hand}, {task.scene.initialState(), along_x})[0],
              0.15 - 0.085, 1e-12);
}

TEST(PairCheck, WithinTheMarginIsRelativeToThePairsSize) {
  const fesd::Scene s = scene();
  EXPECT_TRUE(fesd::withinMargin(s, kDiscThin, 0.29, 0.53));  // margin 0.53 * 0.55 = 0.2915
  EXPECT_FALSE(fesd::withinMargin(s, kDiscThin, 0.3, 0.53));
  EXPECT_TRUE(fesd::withinMargin(s, kDiscFloor, 0.049, 0.1));  // a wall's size: the body's radius
  EXPECT_FALSE(fesd::withinMargin(s, kDiscFloor, 0.051, 0.1));
}

}  // namespace
