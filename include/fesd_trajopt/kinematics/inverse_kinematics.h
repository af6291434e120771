#pragma once

#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/kinematics/kinematic_model.h"

namespace fesd {

struct InverseKinematicsOptions {
  double damping = 1e-2;  ///< mu in J^T (J J^T + mu^2 I)^-1 dp
  /// Largest motion of one joint per iteration (radians or model lengths: the coordinate's change
  /// times its coordinate_scale).
  double max_step = 0.2;
  double tolerance = 1e-10;  ///< distance to the target that counts as reached
  int max_iterations = 500;
  /// A stall: an iteration that shortens the distance by less than this fraction of it.
  double stall_fraction = 1e-9;
  /// Coordinates held still (e.g. passive joints); empty: none.
  std::vector<bool> held;
};

struct InverseKinematicsResult {
  Eigen::VectorXd q;
  double distance;  ///< |p_s(q) - target|
  int iterations;
  bool reached;  ///< distance <= tolerance
};

/// Moves one sphere's centre towards a target by damped least squares from q0, clamping every
/// step at the joint limits (a joint at a limit that the step would push past is held still); a
/// step that does not get closer is retried with more damping, and when none does (a stall: the
/// target is out of reach or the limits stop the way) it ends. Deterministic arithmetic: only
/// fixed-size 3 x 3 solves, no BLAS.
InverseKinematicsResult sphereInverseKinematics(const KinematicModel& model, int sphere,
                                                const Eigen::Vector3d& target,
                                                const Eigen::VectorXd& q0,
                                                const InverseKinematicsOptions& options = {});

}  // namespace fesd
