#include "fesd_trajopt/scene/collision_centres.h"

namespace fesd {

CentreEvaluator::CentreEvaluator(std::shared_ptr<const KinematicModel> robot, int dimension)
    : robot_(std::move(robot)), dimension_(dimension) {}

std::vector<int> CentreEvaluator::variables(const CollisionCentre& centre) const {
  if (centre.source == CollisionCentre::Source::kRobotSphere) return robot_->chainOf(centre.index);
  std::vector<int> result;
  for (int d = 0; d < dimension_; ++d) result.push_back(centre.index + d);
  return result;
}

void CentreEvaluator::setState(const double* x) {
  free_state_ = x;
  if (!robot_) return;
  const int nq = robot_->numCoordinates();
  forwardKinematics(*robot_, Eigen::Map<const Eigen::VectorXd>(x, nq), data_);
}

Eigen::Vector3d CentreEvaluator::inPlane(Eigen::Vector3d w) const {
  if (dimension_ == 2) w.z() = 0.0;
  return w;
}

Eigen::Vector3d CentreEvaluator::position(const CollisionCentre& centre) const {
  if (centre.source == CollisionCentre::Source::kRobotSphere) {
    return inPlane(data_.sphere_centres[centre.index]);
  }
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int d = 0; d < dimension_; ++d) p(d) = free_state_[centre.index + d] + centre.offset(d);
  return p;
}

Eigen::Matrix3Xd CentreEvaluator::jacobian(const CollisionCentre& centre) const {
  if (centre.source == CollisionCentre::Source::kFreeBody) {
    Eigen::Matrix3Xd j = Eigen::Matrix3Xd::Zero(3, dimension_);
    for (int d = 0; d < dimension_; ++d) j(d, d) = 1.0;
    return j;
  }
  const std::vector<int>& chain = robot_->chainOf(centre.index);
  Eigen::Matrix3Xd j(3, chain.size());
  for (size_t c = 0; c < chain.size(); ++c) {
    j.col(c) = inPlane(sphereJacobianColumn(*robot_, data_, centre.index, chain[c]));
  }
  return j;
}

Eigen::VectorXd CentreEvaluator::chainToFull(int sphere, const Eigen::VectorXd& v) const {
  Eigen::VectorXd full = Eigen::VectorXd::Zero(robot_->numCoordinates());
  const std::vector<int>& chain = robot_->chainOf(sphere);
  for (size_t c = 0; c < chain.size(); ++c) full(chain[c]) = v(c);
  return full;
}

Eigen::MatrixXd CentreEvaluator::chainBlock(int sphere, const Eigen::MatrixXd& full) const {
  const std::vector<int>& chain = robot_->chainOf(sphere);
  const int n = static_cast<int>(chain.size());
  Eigen::MatrixXd block(n, n);
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) block(a, b) = full(chain[a], chain[b]);
  }
  return block;
}

Eigen::MatrixXd CentreEvaluator::weightedHessian(const CollisionCentre& centre,
                                                 const Eigen::Vector3d& w) const {
  if (centre.source == CollisionCentre::Source::kFreeBody) {
    return Eigen::MatrixXd::Zero(dimension_, dimension_);
  }
  return chainBlock(centre.index, weightedSphereHessian(*robot_, data_, centre.index, inPlane(w)));
}

Eigen::MatrixXd CentreEvaluator::weightedThirdDerivative(const CollisionCentre& centre,
                                                         const Eigen::Vector3d& w,
                                                         const Eigen::VectorXd& v) const {
  if (centre.source == CollisionCentre::Source::kFreeBody) {
    return Eigen::MatrixXd::Zero(dimension_, dimension_);
  }
  return chainBlock(centre.index,
                    weightedSphereThirdDerivative(*robot_, data_, centre.index, inPlane(w),
                                                  chainToFull(centre.index, v)));
}

}  // namespace fesd
