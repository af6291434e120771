// The shipped robot scenes (examples/robot_scenes.cpp): the planar-arm push is a valid task whose
// disc is in reach of the arm and apart from it at the start; the Panda push is a valid spatial
// task with 118 pairs in reach, no sphere touching the puck or the table at the start.
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/robot_scenes.h"
#include "support/robot_files.h"

namespace {

TEST(RobotScenes, PlanarArmPushIsValidAndInReach) {
  const fesd::SceneTask task = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  EXPECT_EQ(fesd::validateTask(task, {}), "");
  EXPECT_EQ(task.scene.dimension(), 2);
  int modelled_with_disc = 0;
  for (const fesd::PairDecision& d : fesd::decidePairs(task)) {
    modelled_with_disc += d.modelled && d.pair.body == 0;
  }
  EXPECT_GT(modelled_with_disc, 0);
  // The target is within the arm's reach (0.9 less the hand's sphere and the disc).
  EXPECT_LT(task.bodies[0].target.norm(), 0.9 - 0.1);
}

TEST(RobotScenes, PandaPushIsValidSpatialAndInReach) {
  const fesd::SceneTask task = fesd::pandaPushTask(std::make_shared<const fesd::KinematicModel>(
      fesd_test::loadShippedRobot("panda_spherized.urdf")));
  EXPECT_EQ(fesd::validateTask(task, {}), "");
  EXPECT_EQ(task.scene.dimension(), 3);
  EXPECT_EQ(task.scene.robot().spheres.size(), 59u);
  // The puck rests on the table: it slides on it, no pair of theirs.
  EXPECT_EQ(task.scene.supportOf(0), 0);
  const std::vector<fesd::PairDecision> decisions = fesd::decidePairs(task);
  int in_reach = 0;
  for (const fesd::PairDecision& d : decisions) {
    in_reach += d.modelled;
    EXPECT_NE(task.scene.pairName(d.pair), "puck/table");
    // Every sphere of the robot starts apart from the puck and the table.
    EXPECT_GT(task.scene.pairGap(d.pair, task.scene.initialState()), 0.0)
        << task.scene.pairName(d.pair);
  }
  EXPECT_EQ(in_reach, 117);  // the robot's spheres against the puck and the table in reach
}

}  // namespace
