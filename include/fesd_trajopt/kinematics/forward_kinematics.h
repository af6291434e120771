#pragma once

#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/kinematics/kinematic_model.h"

namespace fesd {

/// Per-evaluation buffers of a KinematicModel (the model itself stays constant).
struct KinematicData {
  std::vector<Eigen::Isometry3d> joint_frames;  ///< each joint's moved frame in the world
  std::vector<Eigen::Vector3d> joint_axes;      ///< a_j: each joint's unit axis in the world
  std::vector<Eigen::Vector3d> sphere_centres;  ///< p_s(q)
};

/// Fills data for the configuration q (one entry per coordinate of the model).
void forwardKinematics(const KinematicModel& model, const Eigen::VectorXd& q, KinematicData& data);

/// The frame of a link in the world, from data of forwardKinematics.
Eigen::Isometry3d linkFrame(const KinematicModel& model, const KinematicData& data, int link);

/// dp_s/dq_j (exact, from data of forwardKinematics): a_j x (p_s - o_j) for a revolute joint, a_j
/// for a prismatic one, zero for a joint off the sphere's chain (KinematicModel::chainOf); a_j
/// times the joint's coordinate_scale. Second and third derivatives: SphereDerivatives.
Eigen::Vector3d sphereJacobianColumn(const KinematicModel& model, const KinematicData& data,
                                     int sphere, int joint);
/// The 3 x nq Jacobian dp_s/dq.
Eigen::Matrix3Xd sphereJacobian(const KinematicModel& model, const KinematicData& data, int sphere);

}  // namespace fesd
