// URDF poses as rigid transforms (kinematics/urdf_pose.cpp).
#include <gtest/gtest.h>

#include "fesd_trajopt/kinematics/urdf_pose.h"

namespace {

TEST(UrdfPose, AQuaternionGivenToAFewDigitsBecomesARotation) {
  urdf::Pose pose;
  pose.position = urdf::Vector3(1.0, -2.0, 0.5);
  pose.rotation.x = pose.rotation.y = 0.0;  // 90 degrees about z, to four digits
  pose.rotation.z = pose.rotation.w = 0.7071;
  const Eigen::Isometry3d t = fesd::isometryFromUrdf(pose);
  EXPECT_LT((t.linear().transpose() * t.linear() - Eigen::Matrix3d::Identity()).norm(), 1e-15);
  EXPECT_LT((t * Eigen::Vector3d(1.0, 0.0, 0.0) - Eigen::Vector3d(1.0, -1.0, 0.5)).norm(), 1e-15);
}

}  // namespace
