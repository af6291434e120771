// Reach bounds (kinematics/reach.cpp): lever arms bound |p_s - o_j| at every sampled q (and are
// exact for the stretched planar arm), and no sampled motion within the joint speeds moves a
// sphere farther than its reach bound.
#include <algorithm>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "fesd_trajopt/kinematics/reach.h"
#include "support/robot_files.h"

namespace {

Eigen::VectorXd randomWithinLimits(const fesd::KinematicModel& model, std::mt19937& random) {
  Eigen::VectorXd q(model.numCoordinates());
  for (int j = 0; j < q.size(); ++j) {
    q(j) = std::uniform_real_distribution<double>(std::max(model.joints[j].lower, -M_PI),
                                                  std::min(model.joints[j].upper, M_PI))(random);
  }
  return q;
}

TEST(KinematicReach, LeverArmsBoundTheDistanceToEveryJointAndAreExactWhenStretched) {
  const fesd::KinematicModel arm = fesd_test::loadShippedRobot("planar_arm.urdf");
  const int tip = arm.sphereIndex("hand/sphere_1");
  EXPECT_NEAR(fesd::leverArmBound(arm, tip, arm.jointIndex("shoulder")), 0.9, 1e-15);
  EXPECT_NEAR(fesd::leverArmBound(arm, tip, arm.jointIndex("wrist")), 0.2, 1e-15);
  EXPECT_EQ(fesd::leverArmBound(arm, arm.sphereIndex("upper_arm/sphere_0"), 1), 0.0);  // off

  for (const std::string robot : {"panda_spherized.urdf", "mixed"}) {
    fesd::KinematicModelResult built = fesd::buildKinematicModel(
        robot == "mixed" ? fesd_test::mixedJointsUrdf() : fesd_test::readRobotFile(robot));
    ASSERT_EQ(built.error, "");
    const fesd::KinematicModel& model = built.model;
    std::mt19937 random(5);
    fesd::KinematicData data;
    for (int trial = 0; trial < 50; ++trial) {
      fesd::forwardKinematics(model, randomWithinLimits(model, random), data);
      for (int s = 0; s < static_cast<int>(model.spheres.size()); ++s) {
        for (int j : model.chainOf(s)) {
          EXPECT_LE((data.sphere_centres[s] - data.joint_frames[j].translation()).norm(),
                    fesd::leverArmBound(model, s, j) + 1e-12)
              << robot << " " << model.spheres[s].name << " " << model.joints[j].name;
        }
      }
    }
  }
}

TEST(KinematicReach, NoMotionWithinTheJointSpeedsLeavesTheReachBound) {
  for (const std::string robot : {"planar_arm.urdf", "panda_spherized.urdf", "mixed"}) {
    fesd::KinematicModelResult built = fesd::buildKinematicModel(
        robot == "mixed" ? fesd_test::mixedJointsUrdf() : fesd_test::readRobotFile(robot));
    ASSERT_EQ(built.error, "");
    const fesd::KinematicModel& model = built.model;
    const int nq = model.numCoordinates();
    Eigen::VectorXd velocities(nq);
    for (int j = 0; j < nq; ++j) velocities(j) = std::max(model.joints[j].max_velocity, 0.5);
    const double horizon = 0.8;
    std::mt19937 random(9);
    std::uniform_real_distribution<double> unit(-1.0, 1.0);
    fesd::KinematicData start, end;
    double tightest = 0.0;
    for (int trial = 0; trial < 50; ++trial) {
      const Eigen::VectorXd q0 = randomWithinLimits(model, random);
      Eigen::VectorXd q1 = q0;
      for (int j = 0; j < nq; ++j) {
        q1(j) = std::clamp(q1(j) + velocities(j) * horizon * unit(random), model.joints[j].lower,
                           model.joints[j].upper);
      }
      fesd::forwardKinematics(model, q0, start);
      fesd::forwardKinematics(model, q1, end);
      for (int s = 0; s < static_cast<int>(model.spheres.size()); ++s) {
        const double moved = (end.sphere_centres[s] - start.sphere_centres[s]).norm();
        const double bound = fesd::sphereReachBound(model, s, velocities, horizon);
        EXPECT_LE(moved, bound + 1e-12) << robot << " " << model.spheres[s].name;
        if (bound > 0.0) tightest = std::max(tightest, moved / bound);
      }
    }
    EXPECT_GT(tightest, 0.2) << robot;  // a bound, not a wild overestimate
  }
}

}  // namespace
