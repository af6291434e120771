#include "fesd_trajopt/scene/collision_centres.h"

#include <cstring>
#include <functional>
#include <string_view>

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
  const size_t hash = std::hash<std::string_view>{}(
      std::string_view(reinterpret_cast<const char*>(x), sizeof(double) * nq));  // q's bits
  const auto [first, last] = kept_by_hash_.equal_range(hash);
  for (auto it = first; it != last; ++it) {
    Configuration& kept = kept_[it->second];
    if (std::memcmp(kept.q.data(), x, sizeof(double) * nq) == 0) {
      current_ = &kept;
      return;
    }
  }
  if (used_ == kKinematicsKept) {
    used_ = 0;
    kept_by_hash_.clear();
  }
  if (kept_.empty()) kept_.reserve(kKinematicsKept);  // never moved: current_ points into it
  if (used_ == kept_.size()) kept_.emplace_back();
  current_ = &kept_[used_];
  kept_by_hash_.emplace(hash, static_cast<int>(used_++));
  current_->q = Eigen::Map<const Eigen::VectorXd>(x, nq);
  current_->sphere_count = 0;
  forwardKinematics(*robot_, current_->q, current_->data);
}

const SphereDerivatives& CentreEvaluator::sphereDerivatives(int sphere) const {
  auto& spheres = current_->spheres;
  for (size_t k = 0; k < current_->sphere_count; ++k) {
    if (spheres[k].first == sphere) return spheres[k].second;
  }
  if (current_->sphere_count == spheres.size()) spheres.emplace_back();
  auto& [index, derivatives] = spheres[current_->sphere_count++];
  index = sphere;
  derivatives.compute(*robot_, current_->data, sphere);
  return derivatives;
}

Eigen::Vector3d CentreEvaluator::inPlane(Eigen::Vector3d w) const {
  if (dimension_ == 2) w.z() = 0.0;
  return w;
}

Eigen::Vector3d CentreEvaluator::position(const CollisionCentre& centre) const {
  if (centre.source == CollisionCentre::Source::kRobotSphere) {
    return inPlane(current_->data.sphere_centres[centre.index]);
  }
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int d = 0; d < dimension_; ++d) p(d) = free_state_[centre.index + d] + centre.offset(d);
  return p;
}

void CentreEvaluator::jacobian(const CollisionCentre& centre, Eigen::Matrix3Xd& into) const {
  if (centre.source == CollisionCentre::Source::kFreeBody) {
    into.setZero(3, dimension_);
    for (int d = 0; d < dimension_; ++d) into(d, d) = 1.0;
    return;
  }
  into = sphereDerivatives(centre.index).jacobian();
  if (dimension_ == 2) into.row(2).setZero();
}

void CentreEvaluator::weightedHessian(const CollisionCentre& centre, const Eigen::Vector3d& w,
                                      Eigen::MatrixXd& into) const {
  if (centre.source == CollisionCentre::Source::kFreeBody) {
    into.setZero(dimension_, dimension_);
    return;
  }
  sphereDerivatives(centre.index).weightedHessian(inPlane(w), into);
}

void CentreEvaluator::weightedThirdDerivative(const CollisionCentre& centre,
                                              const Eigen::Vector3d& w, const Eigen::VectorXd& v,
                                              Eigen::MatrixXd& into) const {
  if (centre.source == CollisionCentre::Source::kFreeBody) {
    into.setZero(dimension_, dimension_);
    return;
  }
  sphereDerivatives(centre.index).weightedThirdDerivative(inPlane(w), v, into);
}

}  // namespace fesd
