// Robots read for scenes (scene/robot_from_urdf.cpp): planarity inferred, forced planar refused
// naming the joint that leaves the plane, forced spatial taken.
#include <gtest/gtest.h>

#include "fesd_trajopt/scene/robot_from_urdf.h"
#include "support/robot_files.h"

namespace {

using fesd::PlanarChoice;

TEST(RobotFromUrdf, PlanarityIsInferred) {
  const fesd::RobotForScene arm =
      fesd::robotForScene(fesd_test::readRobotFile("planar_arm.urdf"), PlanarChoice::kInferred);
  ASSERT_EQ(arm.error, "");
  EXPECT_EQ(arm.dimension, 2);
  EXPECT_EQ(arm.robot->numCoordinates(), 3);
  const fesd::RobotForScene panda = fesd::robotForScene(
      fesd_test::readRobotFile("panda_spherized.urdf"), PlanarChoice::kInferred);
  ASSERT_EQ(panda.error, "");
  EXPECT_EQ(panda.dimension, 3);
  EXPECT_EQ(panda.robot->numCoordinates(), 7);  // VAMP fixes the fingers
}

TEST(RobotFromUrdf, ForcingPlanarOnASpatialRobotNamesTheJoint) {
  const fesd::RobotForScene panda =
      fesd::robotForScene(fesd_test::readRobotFile("panda_spherized.urdf"), PlanarChoice::kPlanar);
  EXPECT_EQ(panda.robot, nullptr);
  EXPECT_EQ(panda.error,
            "the scene cannot be planar: joint 'panda_joint2' moves the robot out of the (x, y) "
            "plane");
  const fesd::RobotForScene arm =
      fesd::robotForScene(fesd_test::readRobotFile("planar_arm.urdf"), PlanarChoice::kSpatial);
  ASSERT_EQ(arm.error, "");
  EXPECT_EQ(arm.dimension, 3);
}

TEST(RobotFromUrdf, BrokenUrdfIsRefused) {
  const fesd::RobotForScene broken = fesd::robotForScene("<robot", PlanarChoice::kInferred);
  EXPECT_EQ(broken.robot, nullptr);
  EXPECT_FALSE(broken.error.empty());
}

}  // namespace
