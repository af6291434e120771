// The shipped robot scenes (scene/robot_scenes.cpp): the planar-arm push is a valid task whose
// disc is in reach of the arm and apart from it at the start.
#include <memory>

#include <gtest/gtest.h>

#include "fesd_trajopt/scene/robot_scenes.h"
#include "support/robot_files.h"

namespace {

TEST(RobotScenes, PlanarArmPushIsValidAndInReach) {
  const fesd::RobotTask task = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  EXPECT_EQ(fesd::validateRobotTask(task, {}), "");
  EXPECT_EQ(task.scene.dimension(), 2);
  int modelled_with_disc = 0;
  for (const fesd::RobotPairDecision& d : fesd::decideRobotPairs(task)) {
    modelled_with_disc += d.modelled && d.pair.body == 0;
  }
  EXPECT_GT(modelled_with_disc, 0);
  // The target is within the arm's reach (0.9 less the hand's sphere and the disc).
  EXPECT_LT(task.bodies[0].target.norm(), 0.9 - 0.1);
}

}  // namespace
