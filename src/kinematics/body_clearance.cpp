// A robot's spheres moved clear of other spheres with one sphere held
// (kinematics/body_clearance.h).
#include "fesd_trajopt/kinematics/body_clearance.h"

#include <algorithm>
#include <cmath>

#include "fesd_trajopt/kinematics/forward_kinematics.h"

namespace fesd {
namespace {

/// The robot sphere other than the pusher that cuts deepest into a sphere to clear: its index,
/// the depth, and the unit direction from the sphere it cuts into towards it; sphere -1 when
/// none cuts into one.
struct Intrusion {
  int sphere = -1;
  double depth = 0.0;
  Eigen::Vector3d away = Eigen::Vector3d::Zero();
};

Intrusion deepestIntrusion(const KinematicModel& robot, const KinematicData& data, int pusher,
                           const SpheresToClear& clear) {
  Intrusion deepest;
  for (int s = 0; s < static_cast<int>(robot.spheres.size()); ++s) {
    if (s == pusher) continue;
    for (size_t b = 0; b < clear.centres.size(); ++b) {
      Eigen::Vector3d offset = data.sphere_centres[s] - clear.centres[b];
      if (clear.planar) offset.z() = 0.0;
      const double size = robot.spheres[s].radius + clear.radii[b];
      const double depth = size - offset.norm();
      if (depth > deepest.depth && offset.norm() > 0.0) deepest = {s, depth, offset.normalized()};
    }
  }
  return deepest;
}

/// v less its part that moves the pusher: v - J^T (J J^T + mu^2 I)^-1 J v, J the pusher's
/// Jacobian.
Eigen::VectorXd keepingThePusher(const Eigen::Matrix3Xd& pusher, const Eigen::VectorXd& v,
                                 double damping) {
  Eigen::Matrix3d normal = damping * damping * Eigen::Matrix3d::Identity();
  for (int j = 0; j < pusher.cols(); ++j) normal += pusher.col(j) * pusher.col(j).transpose();
  Eigen::Vector3d moved = Eigen::Vector3d::Zero();
  for (int j = 0; j < pusher.cols(); ++j) moved += pusher.col(j) * v(j);
  const Eigen::Vector3d weights = normal.ldlt().solve(moved);
  Eigen::VectorXd kept = v;
  for (int j = 0; j < pusher.cols(); ++j) kept(j) -= pusher.col(j).dot(weights);
  return kept;
}

/// The step that moves the intruding sphere out by its depth within the pusher's null space,
/// the held joints still, at most ik.max_step per joint (as the IK's steps).
Eigen::VectorXd clearingStep(const KinematicModel& robot, const KinematicData& data, int pusher,
                             const Intrusion& intrusion, const InverseKinematicsOptions& ik) {
  Eigen::Matrix3Xd pusher_jacobian = sphereJacobian(robot, data, pusher);
  Eigen::Matrix3Xd jacobian = sphereJacobian(robot, data, intrusion.sphere);
  for (size_t j = 0; j < ik.held.size(); ++j) {
    if (!ik.held[j]) continue;
    pusher_jacobian.col(j).setZero();
    jacobian.col(j).setZero();
  }
  Eigen::Matrix3Xd rows(3, jacobian.cols());
  for (int i = 0; i < 3; ++i) {
    rows.row(i) =
        keepingThePusher(pusher_jacobian, jacobian.row(i).transpose(), ik.damping).transpose();
  }
  Eigen::Matrix3d normal = ik.damping * ik.damping * Eigen::Matrix3d::Identity();
  for (int j = 0; j < rows.cols(); ++j) normal += rows.col(j) * rows.col(j).transpose();
  const Eigen::Vector3d weights = normal.ldlt().solve(intrusion.depth * intrusion.away);
  Eigen::VectorXd step(rows.cols());
  double largest = 0.0;
  for (int j = 0; j < rows.cols(); ++j) {
    step(j) = rows.col(j).dot(weights);
    largest = std::max(largest, std::abs(robot.joints[j].coordinate_scale * step(j)));
  }
  if (largest > ik.max_step) step *= ik.max_step / largest;
  return step;
}

}  // namespace

Eigen::VectorXd clearOfSpheres(const KinematicModel& robot, int pusher,
                               const Eigen::Vector3d& target, Eigen::VectorXd q,
                               const SpheresToClear& clear, const InverseKinematicsOptions& ik) {
  KinematicData data;
  forwardKinematics(robot, q, data);
  Intrusion deepest = deepestIntrusion(robot, data, pusher, clear);
  double distance = (target - data.sphere_centres[pusher]).norm();
  for (int iteration = 0; deepest.sphere >= 0 && iteration < ik.max_iterations; ++iteration) {
    const Eigen::VectorXd step = clearingStep(robot, data, pusher, deepest, ik);
    if (!(step.cwiseAbs().maxCoeff() > 0.0)) break;
    Eigen::VectorXd candidate = q + step;
    for (int j = 0; j < candidate.size(); ++j) {
      candidate(j) = std::clamp(candidate(j), robot.joints[j].lower, robot.joints[j].upper);
    }
    const InverseKinematicsResult back =
        sphereInverseKinematics(robot, pusher, target, candidate, ik);
    forwardKinematics(robot, back.q, data);
    const Intrusion after = deepestIntrusion(robot, data, pusher, clear);
    if (back.distance > std::max(distance, ik.tolerance) ||
        !(after.sphere < 0 || after.depth < deepest.depth)) {
      break;
    }
    q = back.q;
    distance = back.distance;
    deepest = after;
  }
  return q;
}

}  // namespace fesd
