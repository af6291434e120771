// Where a dragged target may go (src/ros/target_region.cpp): finite poses inside the body's
// bounds and within reach of the scene; the yaw continuous.
#include <gtest/gtest.h>

#include <cmath>
#include <limits>

#include "ros/target_region.h"

namespace {

fesd::SceneTask twoDiscs() {
  fesd::SceneTask task;
  task.scene.bodies().push_back({"pusher", 1.0, Eigen::Vector2d(-2.0, 0.0), true});
  task.scene.bodies().push_back({"object", 1.0, Eigen::Vector2d(0.0, 0.0), false});
  task.bodies.resize(2);
  task.bodies[0].workspace_upper = Eigen::Vector2d(-0.5, INFINITY);
  task.bodies[1].target = Eigen::Vector2d(0.0, 10.0);
  task.bodies[1].target_weight = 1.0;
  return task;
}

const Eigen::Vector4d kLevel(0.0, 0.0, 0.0, 1.0);

TEST(TargetRegion, SpansTheBodiesTheirTargetsAndObstacles) {
  const fesd_ros::TargetRegion region = fesd_ros::targetRegion(twoDiscs(), 1);
  // The box x in [-3, 1], y in [-1, 11]: centre (-1, 5), half diagonal sqrt(4 + 36).
  EXPECT_NEAR(region.centre.x(), -1.0, 1e-12);
  EXPECT_NEAR(region.centre.y(), 5.0, 1e-12);
  EXPECT_NEAR(region.reach, fesd_ros::kTargetReachInSceneSizes * std::sqrt(40.0), 1e-12);
  EXPECT_EQ(region.upper.size(), 0);
}

TEST(TargetRegion, APlanarPoseBecomesAnXYTarget) {
  const fesd_ros::TargetRegion region = fesd_ros::targetRegion(twoDiscs(), 1);
  const fesd_ros::TargetPlacement p =
      fesd_ros::placeTarget(region, {1.0, 9.5, 0.3}, kLevel, 0.0, 0.0);
  EXPECT_EQ(p.refused, "");
  EXPECT_EQ(p.position, Eigen::Vector2d(1.0, 9.5));
}

TEST(TargetRegion, NonFiniteHugeAndOutOfBoundsPosesAreRefused) {
  const fesd::SceneTask task = twoDiscs();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const fesd_ros::TargetRegion object = fesd_ros::targetRegion(task, 1);
  EXPECT_NE(fesd_ros::placeTarget(object, {nan, 1.0, 0.0}, kLevel, 0.0, 0.0).refused, "");
  EXPECT_NE(fesd_ros::placeTarget(object, {1.0, 1.0, 0.0}, {0.0, 0.0, nan, 1.0}, 0.0, 0.0).refused,
            "");
  EXPECT_NE(
      fesd_ros::placeTarget(object, {1.0, 1.0, 0.0}, Eigen::Vector4d::Zero(), 0.0, 0.0).refused,
      "");
  EXPECT_NE(
      fesd_ros::placeTarget(object, {1e12, 1.0, 0.0}, kLevel, 0.0, 0.0).refused.find("scene sizes"),
      std::string::npos);
  const fesd_ros::TargetRegion pusher = fesd_ros::targetRegion(task, 0);
  EXPECT_NE(fesd_ros::placeTarget(pusher, {0.0, 1.0, 0.0}, kLevel, 0.0, 0.0)
                .refused.find("workspace bounds"),
            std::string::npos);
  EXPECT_EQ(fesd_ros::placeTarget(pusher, {-1.0, 1.0, 0.0}, kLevel, 0.0, 0.0).refused, "");
}

TEST(TargetRegion, ASpatialTargetKeepsItsHeight) {
  fesd_ros::TargetRegion region;
  region.dimension = 3;
  region.reach = 10.0;
  const fesd_ros::TargetPlacement p =
      fesd_ros::placeTarget(region, {0.1, 0.2, 5.0}, kLevel, 0.75, 0.0);
  EXPECT_EQ(p.refused, "");
  EXPECT_EQ(p.position, Eigen::Vector3d(0.1, 0.2, 0.75));
}

TEST(TargetRegion, TheYawIsUnwrappedNextToThePreviousOne) {
  fesd_ros::TargetRegion region;
  region.reach = 10.0;
  const double yaw = 3.0;  // a pose at 3 rad after one at 2 pi + 2.9: 2 pi + 3
  const Eigen::Vector4d q(0.0, 0.0, std::sin(0.5 * yaw), std::cos(0.5 * yaw));
  EXPECT_NEAR(fesd_ros::placeTarget(region, {0.0, 0.0, 0.0}, q, 0.0, 2.0 * M_PI + 2.9).yaw,
              2.0 * M_PI + 3.0, 1e-12);
  EXPECT_NEAR(fesd_ros::placeTarget(region, {0.0, 0.0, 0.0}, q, 0.0, 0.0).yaw, 3.0, 1e-12);
}

}  // namespace
