// The shipped robot scenes (examples/robot_scenes.cpp): the planar-arm push is a valid task whose
// disc is in reach of the arm and apart from it at the start; the Panda push is a valid spatial
// task with 118 pairs in reach, no sphere touching the puck or the table at the start; the UR3e's
// and the planar iiwa's are valid and in reach, and the UR3e's plan, whose first round pushes the
// puck from below its centre, holds it on the table.
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/planning/support_check.h"
#include "support/robot_files.h"
#include "support/scene_tasks.h"

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

TEST(RobotScenes, Ur3eAndPlanarIiwaPushesAreValidAndInReach) {
  const fesd::SceneTask ur3e = fesd::ur3ePushTask(std::make_shared<const fesd::KinematicModel>(
      fesd_test::loadShippedRobot("ur3e_spherized.urdf")));
  EXPECT_EQ(fesd::validateTask(ur3e, {}), "");
  EXPECT_EQ(ur3e.scene.supportOf(0), 0);
  const fesd::SceneTask iiwa =
      fesd::planarIiwaPushTask(std::make_shared<const fesd::KinematicModel>(
          fesd_test::loadShippedRobot("planar_iiwa.urdf")));
  EXPECT_EQ(fesd::validateTask(iiwa, {}), "");
  EXPECT_EQ(iiwa.scene.dimension(), 2);
  for (const fesd::SceneTask* task : {&ur3e, &iiwa}) {
    int modelled_with_body = 0;
    for (const fesd::PairDecision& d : fesd::decidePairs(*task)) {
      modelled_with_body += d.modelled && d.pair.body == 0;
      EXPECT_GT(task->scene.pairGap(d.pair, task->scene.initialState()), 0.0)
          << task->scene.pairName(d.pair);
    }
    EXPECT_GT(modelled_with_body, 0);
  }
}

TEST(RobotScenes, TheUr3ePushesThePuckOnlyAsTheTableHoldsIt) {
  // The tool sphere (radius 0.02) reaches below the puck's centre (0.03): the first round's plan
  // pushes from there, the second keeps the lift within the tolerance.
  const fesd::SceneTask task = fesd::ur3ePushTask(std::make_shared<const fesd::KinematicModel>(
      fesd_test::loadShippedRobot("ur3e_spherized.urdf")));
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, {}, fesd_test::robotSolveOptions());
  ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  EXPECT_EQ(outcome.held_on_support, std::vector<int>{0});
  EXPECT_EQ(outcome.supports, std::vector<int>{0});
  EXPECT_LT(outcome.target_distances[0], 1e-3);
  EXPECT_LE(fesd::supportLifts(task, outcome.trajectory, outcome.modelled)[0],
            0.5 * fesd::kSupportLiftTolerance * 0.03 * (1.0 + 1e-6));
  for (const Eigen::VectorXd& x : outcome.trajectory.states) {
    EXPECT_DOUBLE_EQ(task.scene.position(0, x).z(), 0.03);
  }
  EXPECT_GT(outcome.boundary_gap, -1e-9);
}

}  // namespace
