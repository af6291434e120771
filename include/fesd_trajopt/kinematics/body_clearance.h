#pragma once

#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/kinematics/inverse_kinematics.h"
#include "fesd_trajopt/kinematics/kinematic_model.h"

namespace fesd {

/// Spheres a robot should not cut into: centres and radii (e.g. a pushed body's); planar: gaps
/// in x, y only.
struct SpheresToClear {
  std::vector<Eigen::Vector3d> centres;
  std::vector<double> radii;
  bool planar = false;
};

/// The configuration q, whose sphere `pusher` is at `target` (by sphereInverseKinematics), moved
/// with the pusher held there so that the robot's other spheres do not cut into `clear`: the
/// redundant joints turn the rest of the arm out of the body (a pusher on its own joint's axis
/// leaves that link free to swing through the body). Each step moves the deepest intruding sphere
/// out by its depth within the pusher's null space (damped least squares), then IK puts the pusher
/// back; it stops when none intrudes, or a step moves the pusher off its target or leaves the
/// deepest intrusion no shallower. Fixed-size 3 x 3 solves only, as the IK.
Eigen::VectorXd clearOfSpheres(const KinematicModel& robot, int pusher,
                               const Eigen::Vector3d& target, Eigen::VectorXd q,
                               const SpheresToClear& clear, const InverseKinematicsOptions& ik);

}  // namespace fesd
