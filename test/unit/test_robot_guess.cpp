// The robots' first guess (planning/robot_guess.cpp): the pushing sphere by its rule, the sphere
// following the push plan's path through IK at the element boundaries, controls within the
// joints' limits, and the same guess on every call.
#include <memory>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "fesd_trajopt/planning/robot_guess.h"
#include "support/robot_files.h"

namespace {

fesd::SceneTask armPush() {
  return fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
}

std::vector<fesd::ContactPair> modelled(const fesd::SceneTask& task) {
  std::vector<fesd::ContactPair> pairs;
  for (const auto& d : fesd::decidePairs(task)) {
    if (d.modelled) pairs.push_back(d.pair);
  }
  return pairs;
}

TEST(RobotGuess, PushingSphereIsTheToolSphereNearestTheApproachPoint) {
  const fesd::SceneTask task = armPush();
  // The disc at (0.6, 0) goes +y: the approach point is below it. Of the hand's spheres at
  // q0 = (-0.6, 0, 0), sphere_0 (0.75 out) is nearer to it than sphere_1 (0.9 out).
  const int sphere = fesd::pushingSphere(task, 0);
  ASSERT_GE(sphere, 0);
  EXPECT_EQ(task.scene.robot().spheres[sphere].name, "hand/sphere_0");
}

TEST(RobotGuess, SphereFollowsThePlanAndTheGuessRepeats) {
  const fesd::SceneTask task = armPush();
  const std::vector<fesd::ContactPair> pairs = modelled(task);
  const fesd::RobotGuess guess = fesd::planRobotGuess(task, pairs, 2);
  ASSERT_EQ(guess.pushed_body, 0);
  ASSERT_EQ(guess.boundary_joints.size(), static_cast<size_t>(task.num_intervals * 2 + 1));
  EXPECT_EQ(guess.boundary_joints.front(), task.scene.initialJoints());
  // At the end the pushed disc is at its target and the sphere touches it from behind.
  const Eigen::VectorXd end = guess.guess.state(task.horizon);
  EXPECT_LT((end.tail(2) - task.bodies[0].target).norm(), 1e-9);
  fesd::KinematicData data;
  fesd::forwardKinematics(task.scene.robot(), guess.boundary_joints.back(), data);
  const double gap = (data.sphere_centres[guess.pusher_sphere].head(2) - end.tail(2)).norm() -
                     0.05 - task.scene.robot().spheres[guess.pusher_sphere].radius;
  EXPECT_NEAR(gap, 0.0, 1e-6);
  // The push's multiplier sits on the pair of the disc and the pushing sphere.
  const Eigen::VectorXd lambda = guess.guess.multipliers(0.5 * task.horizon);
  ASSERT_EQ(lambda.size(), static_cast<int>(pairs.size()));
  EXPECT_GT(lambda.maxCoeff(), 0.0);
  ASSERT_EQ(guess.guess.controls.size(), static_cast<size_t>(task.num_intervals));
  for (const Eigen::VectorXd& u : guess.guess.controls) {
    for (int j = 0; j < 3; ++j) EXPECT_LE(std::fabs(u(j)), fesd::jointSpeedLimit(task, j));
  }
  const fesd::RobotGuess again = fesd::planRobotGuess(task, pairs, 2);
  EXPECT_EQ(again.boundary_joints, guess.boundary_joints);
  EXPECT_EQ(again.guess.controls, guess.guess.controls);
}

TEST(RobotGuess, WithoutAPushTheJointsGoStraightToTheirTargets) {
  fesd::SceneTask task = armPush();
  task.bodies[0].target_weight = 0.0;
  task.joints[1].target = 0.4;
  task.joints[1].target_weight = 10.0;
  const fesd::RobotGuess guess = fesd::planRobotGuess(task, modelled(task), 2);
  EXPECT_EQ(guess.pusher_sphere, -1);
  EXPECT_NEAR(guess.guess.state(0.5 * task.horizon)(1), 0.2, 1e-12);
  EXPECT_NEAR(guess.guess.state(task.horizon)(1), 0.4, 1e-12);
}

}  // namespace
