#include "support/naive_kinematics.h"

#include <algorithm>

namespace fesd_test {
namespace {

bool onChain(const fesd::KinematicModel& model, int sphere, int joint) {
  const std::vector<int>& chain = model.chainOf(sphere);
  return std::binary_search(chain.begin(), chain.end(), joint);
}

bool isPrismatic(const fesd::KinematicModel& model, int joint) {
  return model.joints[joint].type == fesd::JointType::kPrismatic;
}

/// The world axis of joint i times its turn per unit of its coordinate.
Eigen::Vector3d turningAxis(const fesd::KinematicModel& model, const fesd::KinematicData& data,
                            int i) {
  return model.joints[i].coordinate_scale * data.joint_axes[i];
}

void sortThree(int& i, int& j, int& k) {
  if (i > j) std::swap(i, j);
  if (j > k) std::swap(j, k);
  if (i > j) std::swap(i, j);
}

}  // namespace

// Turning about a revolute joint i turns everything below it, so for i at or above j on the
// chain d col_j / dq_i = a_i x col_j; a prismatic joint only translates, which no column feels.
Eigen::Vector3d sphereSecondDerivative(const fesd::KinematicModel& model,
                                       const fesd::KinematicData& data, int sphere, int i, int j) {
  if (i > j) std::swap(i, j);
  if (!onChain(model, sphere, i) || isPrismatic(model, i)) return Eigen::Vector3d::Zero();
  return turningAxis(model, data, i).cross(fesd::sphereJacobianColumn(model, data, sphere, j));
}

// Differentiating a_j x col_k along i <= j <= k turns a_j and col_k alike (Jacobi identity).
Eigen::Vector3d sphereThirdDerivative(const fesd::KinematicModel& model,
                                      const fesd::KinematicData& data, int sphere, int i, int j,
                                      int k) {
  sortThree(i, j, k);
  if (!onChain(model, sphere, i) || isPrismatic(model, i) || isPrismatic(model, j)) {
    return Eigen::Vector3d::Zero();
  }
  return turningAxis(model, data, i).cross(sphereSecondDerivative(model, data, sphere, j, k));
}

Eigen::MatrixXd weightedSphereHessian(const fesd::KinematicModel& model,
                                      const fesd::KinematicData& data, int sphere,
                                      const Eigen::Vector3d& w) {
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

Eigen::MatrixXd weightedSphereThirdDerivative(const fesd::KinematicModel& model,
                                              const fesd::KinematicData& data, int sphere,
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

}  // namespace fesd_test
