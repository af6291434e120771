#include "fesd_trajopt/kinematics/planarity.h"

#include <cmath>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/kinematics/forward_kinematics.h"

namespace fesd {

std::string firstJointLeavingPlane(const KinematicModel& model) {
  const int nq = model.numCoordinates();
  // Only joints that move a sphere matter.
  std::vector<bool> moves_a_sphere(nq, false);
  for (std::size_t s = 0; s < model.spheres.size(); ++s) {
    for (int j : model.chainOf(static_cast<int>(s))) moves_a_sphere[j] = true;
  }
  KinematicData data;
  forwardKinematics(model, Eigen::VectorXd::Zero(nq), data);
  constexpr double kTolerance = 1e-9;
  for (int j = 0; j < nq; ++j) {
    if (!moves_a_sphere[j]) continue;
    const Eigen::Vector3d& axis = data.joint_axes[j];
    const bool in_plane = model.joints[j].type == JointType::kPrismatic
                              ? std::abs(axis.z()) <= kTolerance
                              : axis.head<2>().norm() <= kTolerance;
    if (!in_plane) return model.joints[j].name;
  }
  return "";
}

}  // namespace fesd
