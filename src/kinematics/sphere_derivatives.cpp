#include "fesd_trajopt/kinematics/sphere_derivatives.h"

#include <algorithm>

namespace fesd {

void SphereDerivatives::compute(const KinematicModel& model, const KinematicData& data,
                                int sphere) {
  const std::vector<int>& chain = model.chainOf(sphere);
  size_ = static_cast<int>(chain.size());
  jacobian_.resize(3, size_);
  second_.resize(static_cast<size_t>(size_) * size_);
  turning_axes_.resize(size_);
  for (int a = 0; a < size_; ++a) {
    const int joint = chain[a];
    const bool prismatic = model.joints[joint].type == JointType::kPrismatic;
    turning_axes_[a] =
        prismatic ? Eigen::Vector3d::Zero()
                  : Eigen::Vector3d(model.joints[joint].coordinate_scale * data.joint_axes[joint]);
    jacobian_.col(a) = sphereJacobianColumn(model, data, sphere, joint);
  }
  for (int a = 0; a < size_; ++a) {
    for (int b = a; b < size_; ++b) {
      second_[a * size_ + b] = turning_axes_[a].cross(jacobian_.col(b));
      second_[b * size_ + a] = second_[a * size_ + b];
    }
  }
}

void SphereDerivatives::weightedHessian(const Eigen::Vector3d& w, Eigen::MatrixXd& hessian) const {
  hessian.resize(size_, size_);
  for (int a = 0; a < size_; ++a) {
    for (int b = a; b < size_; ++b) hessian(a, b) = hessian(b, a) = w.dot(second(a, b));
  }
}

// w . (a_i x S_jk) for the sorted i <= j <= k; zero when joint i (or j, whose S_jk is then zero)
// is prismatic. Summed in the order of the entry-by-entry formula, to its bits.
void SphereDerivatives::weightedThirdDerivative(const Eigen::Vector3d& w, const Eigen::VectorXd& v,
                                                Eigen::MatrixXd& result) const {
  result.setZero(size_, size_);
  for (int i = 0; i < size_; ++i) {
    if (v(i) == 0.0) continue;
    for (int a = 0; a < size_; ++a) {
      for (int b = a; b < size_; ++b) {
        const int first = std::min(i, a), last = std::max(i, b);
        const int middle = i + a + b - first - last;
        const double value = v(i) * w.dot(turning_axes_[first].cross(second(middle, last)));
        result(a, b) += value;
        if (a != b) result(b, a) += value;
      }
    }
  }
}

}  // namespace fesd
