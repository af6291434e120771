#include "fesd_trajopt/kinematics/reach.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace fesd {

double leverArmBound(const KinematicModel& model, int sphere, int joint) {
  const std::vector<int>& chain = model.chainOf(sphere);
  const auto position = std::find(chain.begin(), chain.end(), joint);
  if (position == chain.end()) return 0.0;
  // p_s - o_j is the sum of the fixed translations below j, turned by the joints in between,
  // and of the prismatic displacements q_k a_k below j (a prismatic j moves o_j with p_s).
  double bound = model.spheres[sphere].joint_centre.norm();
  for (auto below = position + 1; below != chain.end(); ++below) {
    const KinematicJoint& next = model.joints[*below];
    bound += next.origin.translation().norm();
    if (next.type == JointType::kPrismatic) {
      bound += next.coordinate_scale * std::max(std::abs(next.lower), std::abs(next.upper));
    }
  }
  return bound;
}

double sphereReachBound(const KinematicModel& model, int sphere, const Eigen::VectorXd& velocities,
                        double horizon) {
  double bound = 0.0;
  for (int j : model.chainOf(sphere)) {
    const KinematicJoint& joint = model.joints[j];
    const double speed_per_unit =
        joint.coordinate_scale *
        (joint.type == JointType::kPrismatic ? 1.0 : leverArmBound(model, sphere, j));
    bound += std::abs(velocities(j)) * horizon * speed_per_unit;
  }
  return bound;
}

double robotReach(const KinematicModel& model) {
  double reach = 0.0;
  for (int s = 0; s < static_cast<int>(model.spheres.size()); ++s) {
    if (model.spheres[s].link < 0) continue;
    for (int j : model.chainOf(s)) {
      const KinematicJoint& joint = model.joints[j];
      if (joint.type == JointType::kPrismatic) continue;
      reach = std::max(reach, joint.coordinate_scale * leverArmBound(model, s, j));
    }
  }
  return reach > 0.0 ? reach : 1.0;
}

}  // namespace fesd
