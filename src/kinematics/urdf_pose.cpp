#include "fesd_trajopt/kinematics/urdf_pose.h"

namespace fesd {

Eigen::Isometry3d isometryFromUrdf(const urdf::Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() << pose.position.x, pose.position.y, pose.position.z;
  t.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  return t;
}

}  // namespace fesd
