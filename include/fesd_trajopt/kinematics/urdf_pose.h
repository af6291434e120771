#pragma once

#include <urdf_model/pose.h>
#include <Eigen/Geometry>

namespace fesd {

/// A URDF pose (origin of a joint or a collision) as a rigid transform; the quaternion is
/// normalised, since URDF files give rotations to a few digits.
Eigen::Isometry3d isometryFromUrdf(const urdf::Pose& pose);

}  // namespace fesd
