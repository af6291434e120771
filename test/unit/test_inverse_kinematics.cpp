// Damped least-squares inverse kinematics for one sphere centre
// (kinematics/inverse_kinematics.cpp): reachable targets met to 1e-8 on the planar arm and the
// Panda, unreachable ones end cleanly at the closest point (stretched out, or against a joint
// limit), held joints stay put, and the result is bitwise repeatable.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "fesd_trajopt/kinematics/inverse_kinematics.h"
#include "support/robot_files.h"

namespace {

Eigen::Vector3d centreAt(const fesd::KinematicModel& model, int sphere, const Eigen::VectorXd& q) {
  fesd::KinematicData data;
  fesd::forwardKinematics(model, q, data);
  return data.sphere_centres[sphere];
}

bool withinLimits(const fesd::KinematicModel& model, const Eigen::VectorXd& q) {
  for (int j = 0; j < model.numCoordinates(); ++j) {
    if (q(j) < model.joints[j].lower || q(j) > model.joints[j].upper) return false;
  }
  return true;
}

TEST(InverseKinematics, ReachablePointsAreMetOnThePlanarArmAndThePanda) {
  const fesd::KinematicModel arm = fesd_test::loadShippedRobot("planar_arm.urdf");
  const int tip = arm.sphereIndex("hand/sphere_1");
  const Eigen::Vector3d target = centreAt(arm, tip, Eigen::Vector3d(0.7, -1.1, 0.9));
  const fesd::InverseKinematicsResult arm_result =
      fesd::sphereInverseKinematics(arm, tip, target, Eigen::Vector3d::Zero());
  EXPECT_TRUE(arm_result.reached);
  EXPECT_LT((centreAt(arm, tip, arm_result.q) - target).norm(), 1e-8);
  EXPECT_TRUE(withinLimits(arm, arm_result.q));

  const fesd::KinematicModel panda = fesd_test::loadShippedRobot("panda_spherized.urdf");
  const int finger = panda.sphereIndex("panda_leftfinger/sphere_1");
  Eigen::VectorXd ready(7);
  ready << 0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785;
  Eigen::VectorXd moved = ready;
  moved.head<3>() += Eigen::Vector3d(0.4, 0.3, -0.2);
  const Eigen::Vector3d panda_target = centreAt(panda, finger, moved);
  const fesd::InverseKinematicsResult panda_result =
      fesd::sphereInverseKinematics(panda, finger, panda_target, ready);
  EXPECT_TRUE(panda_result.reached);
  EXPECT_LT((centreAt(panda, finger, panda_result.q) - panda_target).norm(), 1e-8);
  EXPECT_TRUE(withinLimits(panda, panda_result.q));
}

TEST(InverseKinematics, HeldJointsStayWhereTheyStart) {
  const fesd::KinematicModel arm = fesd_test::loadShippedRobot("planar_arm.urdf");
  const int tip = arm.sphereIndex("hand/sphere_1");
  // Reachable with the wrist held at 0.3: the target is where q = (0.7, -1.1, 0.3) puts the tip.
  const Eigen::Vector3d target = centreAt(arm, tip, Eigen::Vector3d(0.7, -1.1, 0.3));
  fesd::InverseKinematicsOptions options;
  options.held = {false, false, true};
  const fesd::InverseKinematicsResult result =
      fesd::sphereInverseKinematics(arm, tip, target, Eigen::Vector3d(0.0, 0.0, 0.3), options);
  EXPECT_TRUE(result.reached);
  EXPECT_EQ(result.q(2), 0.3);
  EXPECT_LT((centreAt(arm, tip, result.q) - target).norm(), 1e-8);
}

TEST(InverseKinematics, UnreachablePointsEndCleanlyAtTheClosestPointAndRepeatBitwise) {
  const fesd::KinematicModel arm = fesd_test::loadShippedRobot("planar_arm.urdf");
  const int tip = arm.sphereIndex("hand/sphere_1");
  const Eigen::Vector3d far(2.0, 1.0, 0.0);  // the tip reaches 0.4 + 0.3 + 0.2 = 0.9 m
  fesd::InverseKinematicsOptions options;
  const fesd::InverseKinematicsResult result =
      fesd::sphereInverseKinematics(arm, tip, far, Eigen::Vector3d(0.1, 0.2, 0.3), options);
  EXPECT_FALSE(result.reached);
  EXPECT_LT(result.iterations, options.max_iterations);  // stopped by the stall, not the cap
  EXPECT_NEAR(result.distance, far.norm() - 0.9, 1e-6);
  EXPECT_TRUE(withinLimits(arm, result.q));

  const fesd::InverseKinematicsResult again =
      fesd::sphereInverseKinematics(arm, tip, far, Eigen::Vector3d(0.1, 0.2, 0.3), options);
  EXPECT_EQ(again.iterations, result.iterations);
  EXPECT_TRUE((again.q.array() == result.q.array()).all());

  // Behind the base, past the shoulder's limit of -2.8 rad: the shoulder stops at its limit and
  // the rest of the arm (0.5 m) stretches from the elbow towards the target.
  const Eigen::Vector3d behind(-0.9, -0.05, 0.0);
  const fesd::InverseKinematicsResult limited =
      fesd::sphereInverseKinematics(arm, tip, behind, Eigen::Vector3d::Zero(), options);
  const Eigen::Vector3d elbow(0.4 * std::cos(-2.8), 0.4 * std::sin(-2.8), 0.0);
  EXPECT_FALSE(limited.reached);
  EXPECT_LT(limited.iterations, options.max_iterations);
  EXPECT_EQ(limited.q(0), -2.8);
  EXPECT_NEAR(limited.distance, (behind - elbow).norm() - 0.5, 1e-6);
  EXPECT_TRUE(withinLimits(arm, limited.q));
}

}  // namespace
