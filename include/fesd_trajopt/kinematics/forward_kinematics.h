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

// Derivatives of a sphere centre p_s(q), exact, from data of forwardKinematics. Joints off the
// sphere's chain (KinematicModel::chainOf) give zero; the derivatives are symmetric in their
// joint indices, which may come in any order.

/// dp_s/dq_j: a_j x (p_s - o_j) for a revolute joint, a_j for a prismatic one.
Eigen::Vector3d sphereJacobianColumn(const KinematicModel& model, const KinematicData& data,
                                     int sphere, int joint);
/// The 3 x nq Jacobian dp_s/dq.
Eigen::Matrix3Xd sphereJacobian(const KinematicModel& model, const KinematicData& data, int sphere);
/// d^2 p_s / dq_i dq_j.
Eigen::Vector3d sphereSecondDerivative(const KinematicModel& model, const KinematicData& data,
                                       int sphere, int i, int j);
/// d^3 p_s / dq_i dq_j dq_k.
Eigen::Vector3d sphereThirdDerivative(const KinematicModel& model, const KinematicData& data,
                                      int sphere, int i, int j, int k);
/// The nq x nq matrix sum_m w_m d^2 p_{s,m} / dq dq: the Hessian of w . p_s(q) for fixed w.
Eigen::MatrixXd weightedSphereHessian(const KinematicModel& model, const KinematicData& data,
                                      int sphere, const Eigen::Vector3d& w);
/// The derivative of weightedSphereHessian along the direction v (fixed w): the nq x nq matrix
/// sum_i v_i sum_m w_m d^3 p_{s,m} / dq_i dq dq, which the exact Hessian of a Lagrangian holding
/// grad c(q) lambda needs.
Eigen::MatrixXd weightedSphereThirdDerivative(const KinematicModel& model,
                                              const KinematicData& data, int sphere,
                                              const Eigen::Vector3d& w, const Eigen::VectorXd& v);

/// c = |p_s(q) - p_o|^2 - (r_s + r_o)^2 for a point p_o held fixed, with its gradient
/// 2 J^T (p_s - p_o) and Hessian 2 J^T J + 2 sum_m (p_s - p_o)_m d^2 p_{s,m} / dq dq in q. (Its
/// derivatives in p_o are -2 (p_s - p_o), -2 J^T and 2 I.)
struct SphereClearance {
  double value;
  Eigen::VectorXd gradient;
  Eigen::MatrixXd hessian;
};
SphereClearance sphereClearance(const KinematicModel& model, const KinematicData& data, int sphere,
                                const Eigen::Vector3d& point, double radius);

}  // namespace fesd
