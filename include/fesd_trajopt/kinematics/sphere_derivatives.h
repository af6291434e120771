#pragma once

#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/kinematics/forward_kinematics.h"

namespace fesd {

/// A sphere centre's derivatives in the joints of its chain (chain-local indices 0..n-1, root
/// first), computed once per configuration and shared by every pair and every derivative order
/// that needs them: the Jacobian's columns and the second derivatives, from which the weighted
/// Hessian and third derivative follow by dot products alone (the chain's structure: a joint's
/// motion turns everything below it, so d col_j / dq_i = a_i x col_j for i <= j, and the third
/// derivative along i <= j <= k is a_i x d^2 p / dq_j dq_k; zero where i or j is prismatic). The
/// Jacobian's columns are sphereJacobianColumn's; no search of the chain per entry, no
/// allocation once sized for the longest chain.
class SphereDerivatives {
 public:
  /// Fills the derivatives of `sphere` at the configuration of `data` (forwardKinematics).
  void compute(const KinematicModel& model, const KinematicData& data, int sphere);

  int size() const { return size_; }
  /// dp/dq_chain: 3 x size().
  const Eigen::Matrix3Xd& jacobian() const { return jacobian_; }
  /// d^2 p / dq_a dq_b (chain-local, symmetric).
  const Eigen::Vector3d& second(int a, int b) const { return second_[a * size_ + b]; }
  /// The Hessian of w . p in the chain's joints, into `hessian` (size() x size()).
  void weightedHessian(const Eigen::Vector3d& w, Eigen::MatrixXd& hessian) const;
  /// Its derivative along v (chain-local, w fixed): sum_i v_i sum_m w_m d^3 p_m / dq_i dq dq.
  void weightedThirdDerivative(const Eigen::Vector3d& w, const Eigen::VectorXd& v,
                               Eigen::MatrixXd& result) const;

 private:
  int size_ = 0;
  Eigen::Matrix3Xd jacobian_;
  std::vector<Eigen::Vector3d> second_;  ///< size x size, row-major, both triangles
  /// Each joint's axis in the world times its coordinate_scale for a revolute joint, zero for a
  /// prismatic one (which only translates: no column below it turns).
  std::vector<Eigen::Vector3d> turning_axes_;
};

}  // namespace fesd
