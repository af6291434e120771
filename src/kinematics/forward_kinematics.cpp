#include "fesd_trajopt/kinematics/forward_kinematics.h"

#include <algorithm>

namespace fesd {
namespace {

bool onChain(const KinematicModel& model, int sphere, int joint) {
  const std::vector<int>& chain = model.chainOf(sphere);
  return std::binary_search(chain.begin(), chain.end(), joint);
}

bool isPrismatic(const KinematicModel& model, int joint) {
  return model.joints[joint].type == JointType::kPrismatic;
}

}  // namespace

void forwardKinematics(const KinematicModel& model, const Eigen::VectorXd& q, KinematicData& data) {
  const int nq = model.numCoordinates();
  data.joint_frames.resize(nq);
  data.joint_axes.resize(nq);
  for (int j = 0; j < nq; ++j) {
    const KinematicJoint& joint = model.joints[j];
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    const double moved = joint.coordinate_scale * q(j);
    if (joint.type == JointType::kPrismatic) {
      motion.translation() = moved * joint.axis;
    } else {
      motion.linear() = Eigen::AngleAxisd(moved, joint.axis).toRotationMatrix();
    }
    const Eigen::Isometry3d above =
        joint.parent < 0 ? Eigen::Isometry3d::Identity() : data.joint_frames[joint.parent];
    data.joint_frames[j] = above * joint.origin * motion;
    data.joint_axes[j] = data.joint_frames[j].linear() * joint.axis;
  }
  data.sphere_centres.resize(model.spheres.size());
  for (std::size_t s = 0; s < model.spheres.size(); ++s) {
    const int joint = model.links[model.spheres[s].link].joint;
    const Eigen::Vector3d& centre = model.spheres[s].joint_centre;
    data.sphere_centres[s] =
        joint < 0 ? centre : Eigen::Vector3d(data.joint_frames[joint] * centre);
  }
}

Eigen::Isometry3d linkFrame(const KinematicModel& model, const KinematicData& data, int link) {
  const KinematicLink& entry = model.links[link];
  return entry.joint < 0 ? entry.offset : data.joint_frames[entry.joint] * entry.offset;
}

Eigen::Vector3d sphereJacobianColumn(const KinematicModel& model, const KinematicData& data,
                                     int sphere, int joint) {
  if (!onChain(model, sphere, joint)) return Eigen::Vector3d::Zero();
  const Eigen::Vector3d axis = model.joints[joint].coordinate_scale * data.joint_axes[joint];
  if (isPrismatic(model, joint)) return axis;
  return axis.cross(data.sphere_centres[sphere] - data.joint_frames[joint].translation());
}

Eigen::Matrix3Xd sphereJacobian(const KinematicModel& model, const KinematicData& data,
                                int sphere) {
  Eigen::Matrix3Xd jacobian = Eigen::Matrix3Xd::Zero(3, model.numCoordinates());
  for (int j : model.chainOf(sphere)) {
    jacobian.col(j) = sphereJacobianColumn(model, data, sphere, j);
  }
  return jacobian;
}

}  // namespace fesd
