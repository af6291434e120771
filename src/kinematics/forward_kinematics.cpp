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

void sortThree(int& i, int& j, int& k) {
  if (i > j) std::swap(i, j);
  if (j > k) std::swap(j, k);
  if (i > j) std::swap(i, j);
}

}  // namespace

void forwardKinematics(const KinematicModel& model, const Eigen::VectorXd& q, KinematicData& data) {
  const int nq = model.numCoordinates();
  data.joint_frames.resize(nq);
  data.joint_axes.resize(nq);
  for (int j = 0; j < nq; ++j) {
    const KinematicJoint& joint = model.joints[j];
    Eigen::Isometry3d motion = Eigen::Isometry3d::Identity();
    if (joint.type == JointType::kPrismatic) {
      motion.translation() = q(j) * joint.axis;
    } else {
      motion.linear() = Eigen::AngleAxisd(q(j), joint.axis).toRotationMatrix();
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
  const Eigen::Vector3d& axis = data.joint_axes[joint];
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

// Turning about a revolute joint i turns everything below it, so for i at or above j on the
// chain d col_j / dq_i = a_i x col_j; a prismatic joint only translates, which no column feels.
Eigen::Vector3d sphereSecondDerivative(const KinematicModel& model, const KinematicData& data,
                                       int sphere, int i, int j) {
  if (i > j) std::swap(i, j);
  if (!onChain(model, sphere, i) || isPrismatic(model, i)) return Eigen::Vector3d::Zero();
  return data.joint_axes[i].cross(sphereJacobianColumn(model, data, sphere, j));
}

// Differentiating a_j x col_k along i <= j <= k turns a_j and col_k alike (Jacobi identity).
Eigen::Vector3d sphereThirdDerivative(const KinematicModel& model, const KinematicData& data,
                                      int sphere, int i, int j, int k) {
  sortThree(i, j, k);
  if (!onChain(model, sphere, i) || isPrismatic(model, i) || isPrismatic(model, j)) {
    return Eigen::Vector3d::Zero();
  }
  return data.joint_axes[i].cross(sphereSecondDerivative(model, data, sphere, j, k));
}

Eigen::MatrixXd weightedSphereHessian(const KinematicModel& model, const KinematicData& data,
                                      int sphere, const Eigen::Vector3d& w) {
  const int nq = model.numCoordinates();
  Eigen::MatrixXd hessian = Eigen::MatrixXd::Zero(nq, nq);
  const std::vector<int>& chain = model.chainOf(sphere);
  for (std::size_t a = 0; a < chain.size(); ++a) {
    for (std::size_t b = a; b < chain.size(); ++b) {
      const double value = w.dot(sphereSecondDerivative(model, data, sphere, chain[a], chain[b]));
      hessian(chain[a], chain[b]) = value;
      hessian(chain[b], chain[a]) = value;
    }
  }
  return hessian;
}

Eigen::MatrixXd weightedSphereThirdDerivative(const KinematicModel& model,
                                              const KinematicData& data, int sphere,
                                              const Eigen::Vector3d& w, const Eigen::VectorXd& v) {
  const int nq = model.numCoordinates();
  Eigen::MatrixXd result = Eigen::MatrixXd::Zero(nq, nq);
  const std::vector<int>& chain = model.chainOf(sphere);
  for (int i : chain) {
    if (v(i) == 0.0) continue;
    for (std::size_t a = 0; a < chain.size(); ++a) {
      for (std::size_t b = a; b < chain.size(); ++b) {
        const double value =
            v(i) * w.dot(sphereThirdDerivative(model, data, sphere, i, chain[a], chain[b]));
        result(chain[a], chain[b]) += value;
        if (a != b) result(chain[b], chain[a]) += value;
      }
    }
  }
  return result;
}

SphereClearance sphereClearance(const KinematicModel& model, const KinematicData& data, int sphere,
                                const Eigen::Vector3d& point, double radius) {
  const Eigen::Vector3d gap = data.sphere_centres[sphere] - point;
  const double reach = model.spheres[sphere].radius + radius;
  const Eigen::Matrix3Xd jacobian = sphereJacobian(model, data, sphere);
  return {gap.squaredNorm() - reach * reach, 2.0 * jacobian.transpose() * gap,
          2.0 * jacobian.transpose() * jacobian +
              2.0 * weightedSphereHessian(model, data, sphere, gap)};
}

}  // namespace fesd
