// A robot's spheres moved clear of a body with one sphere held (kinematics/body_clearance.cpp):
// the planar iiwa pushing with the sphere on its last joint's axis, its last link through a disc,
// turns that link out (no other sphere cuts into the disc, the pusher stays within 1e-8 of
// its target, the joints within their limits); with the last joint held nothing can turn it out
// and the pusher still stays.
#include <algorithm>
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/kinematics/body_clearance.h"
#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "support/robot_files.h"

namespace {

/// The smallest planar gap of the robot's spheres but the pusher to the disc.
double smallestSlack(const fesd::KinematicModel& robot, int pusher, const Eigen::VectorXd& q,
                     const fesd::SpheresToClear& disc) {
  fesd::KinematicData data;
  fesd::forwardKinematics(robot, q, data);
  double slack = 1e9;
  for (int s = 0; s < static_cast<int>(robot.spheres.size()); ++s) {
    if (s == pusher) continue;
    Eigen::Vector3d offset = data.sphere_centres[s] - disc.centres[0];
    offset.z() = 0.0;
    const double size = robot.spheres[s].radius + disc.radii[0];
    slack = std::min(slack, offset.norm() - size);
  }
  return slack;
}

class BodyClearance : public ::testing::Test {
 protected:
  const fesd::KinematicModel iiwa = fesd_test::loadShippedRobot("planar_iiwa.urdf");
  const int pusher = iiwa.sphereIndex("link_6/sphere_0");  // on joint 6's axis
  const Eigen::VectorXd bent = Eigen::Vector3d(0.3, -0.8, 0.0);
  // A disc just beside link 6's far sphere, on the side joint 6 turns it towards first.
  fesd::SpheresToClear disc{
      {sphereAt("link_6/sphere_2") + Eigen::Vector3d(0.0, 0.02, 0.0)}, {0.04}, true};

  Eigen::Vector3d sphereAt(const std::string& name) const {
    fesd::KinematicData data;
    fesd::forwardKinematics(iiwa, Eigen::Vector3d(0.3, -0.8, 0.0), data);
    return data.sphere_centres[iiwa.sphereIndex(name)];
  }

  Eigen::Vector3d pusherAt(const Eigen::VectorXd& q) const {
    fesd::KinematicData data;
    fesd::forwardKinematics(iiwa, q, data);
    return data.sphere_centres[pusher];
  }
};

TEST_F(BodyClearance, TheLastLinkTurnsOutOfTheDiscWithThePusherHeld) {
  ASSERT_LT(smallestSlack(iiwa, pusher, bent, disc), -0.03);  // link 6 cuts the disc
  const Eigen::Vector3d target = pusherAt(bent);
  const Eigen::VectorXd q =
      fesd::clearOfSpheres(iiwa, pusher, target, bent, disc, fesd::InverseKinematicsOptions{});
  EXPECT_GE(smallestSlack(iiwa, pusher, q, disc), -1e-12);
  EXPECT_LT((pusherAt(q) - target).norm(), 1e-8);
  EXPECT_GT(std::abs(q(2)), 0.3);  // the last joint turned
  for (int j = 0; j < 3; ++j) {
    EXPECT_GE(q(j), iiwa.joints[j].lower);
    EXPECT_LE(q(j), iiwa.joints[j].upper);
  }
}

TEST_F(BodyClearance, WithTheLastJointHeldThePusherStays) {
  fesd::InverseKinematicsOptions ik;
  ik.held = {false, false, true};
  const Eigen::Vector3d target = pusherAt(bent);
  const Eigen::VectorXd q = fesd::clearOfSpheres(iiwa, pusher, target, bent, disc, ik);
  EXPECT_EQ(q(2), 0.0);
  EXPECT_LT((pusherAt(q) - target).norm(), 1e-8);
  EXPECT_LT(smallestSlack(iiwa, pusher, q, disc), 0.0);  // no way out without joint 6
}

}  // namespace
