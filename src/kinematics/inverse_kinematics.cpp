#include "fesd_trajopt/kinematics/inverse_kinematics.h"

#include <algorithm>

#include "fesd_trajopt/kinematics/forward_kinematics.h"

namespace fesd {
namespace {

/// dq = J^T (J J^T + mu^2 I)^-1 dp with J J^T accumulated column by column (fixed 3 x 3).
Eigen::VectorXd dampedStep(const Eigen::Matrix3Xd& jacobian, const Eigen::Vector3d& error,
                           double damping) {
  Eigen::Matrix3d normal = damping * damping * Eigen::Matrix3d::Identity();
  for (int j = 0; j < jacobian.cols(); ++j) normal += jacobian.col(j) * jacobian.col(j).transpose();
  const Eigen::Vector3d weights = normal.ldlt().solve(error);
  Eigen::VectorXd step(jacobian.cols());
  for (int j = 0; j < jacobian.cols(); ++j) step(j) = jacobian.col(j).dot(weights);
  return step;
}

/// The damped step with the joints that sit at a limit and would be pushed past it held still:
/// clamping the step afterwards would waste the part of the motion meant for them.
Eigen::VectorXd stepWithinLimits(const KinematicModel& model, const Eigen::VectorXd& q,
                                 Eigen::Matrix3Xd jacobian, const Eigen::Vector3d& error,
                                 double damping) {
  for (;;) {
    const Eigen::VectorXd step = dampedStep(jacobian, error, damping);
    bool locked = false;
    for (int j = 0; j < model.numCoordinates(); ++j) {
      const bool outwards = (q(j) <= model.joints[j].lower && step(j) < 0.0) ||
                            (q(j) >= model.joints[j].upper && step(j) > 0.0);
      if (outwards) {
        jacobian.col(j).setZero();  // its step is then exactly 0
        locked = true;
      }
    }
    if (!locked) return step;
  }
}

Eigen::VectorXd clampToLimits(const KinematicModel& model, Eigen::VectorXd q) {
  for (int j = 0; j < model.numCoordinates(); ++j) {
    q(j) = std::clamp(q(j), model.joints[j].lower, model.joints[j].upper);
  }
  return q;
}

}  // namespace

InverseKinematicsResult sphereInverseKinematics(const KinematicModel& model, int sphere,
                                                const Eigen::Vector3d& target,
                                                const Eigen::VectorXd& q0,
                                                const InverseKinematicsOptions& options) {
  // A rejected step is retried with ten times the damping (towards a short gradient step), an
  // accepted one relaxes it again: near a singularity the undamped direction is dominated by
  // the stretch the arm cannot make, and shortening it alone would keep that direction.
  constexpr int kDampingIncreases = 12;
  KinematicData data;
  InverseKinematicsResult result{clampToLimits(model, q0), 0.0, 0, false};
  forwardKinematics(model, result.q, data);
  result.distance = (target - data.sphere_centres[sphere]).norm();
  double damping = options.damping;
  while (result.distance > options.tolerance && result.iterations < options.max_iterations) {
    ++result.iterations;
    Eigen::Matrix3Xd jacobian = sphereJacobian(model, data, sphere);
    for (size_t j = 0; j < options.held.size(); ++j) {
      if (options.held[j]) jacobian.col(j).setZero();  // its step is then exactly 0
    }
    const Eigen::Vector3d error = target - data.sphere_centres[sphere];
    bool progressed = false;
    for (int increase = 0; increase <= kDampingIncreases && !progressed; ++increase) {
      Eigen::VectorXd step = stepWithinLimits(model, result.q, jacobian, error, damping);
      double largest = 0.0;  // the joints' motion (coordinate_scale per unit)
      for (int j = 0; j < step.size(); ++j) {
        largest = std::max(largest, std::abs(model.joints[j].coordinate_scale * step(j)));
      }
      if (largest > options.max_step) step *= options.max_step / largest;
      const Eigen::VectorXd candidate = clampToLimits(model, result.q + step);
      forwardKinematics(model, candidate, data);
      const double distance = (target - data.sphere_centres[sphere]).norm();
      if (distance < result.distance * (1.0 - options.stall_fraction)) {
        result.q = candidate;
        result.distance = distance;
        damping = std::max(options.damping, 0.1 * damping);
        progressed = true;
      } else {
        damping *= 10.0;
      }
    }
    if (!progressed) {
      forwardKinematics(model, result.q, data);
      break;
    }
  }
  result.reached = result.distance <= options.tolerance;
  return result;
}

}  // namespace fesd
