#include "fesd_trajopt/scene/collision_centres.h"

#include <cmath>
#include <cstring>
#include <functional>
#include <string_view>

namespace fesd {

CentreEvaluator::CentreEvaluator(std::shared_ptr<const KinematicModel> robot, int dimension)
    : robot_(std::move(robot)), dimension_(dimension) {}

namespace {

/// A turning body's yaw and its offset turned by it (about z; z stays).
struct TurnedOffset {
  double inverse_radius;
  Eigen::Vector3d turned;  ///< R(yaw) offset
  Eigen::Vector3d normal;  ///< d/dyaw R(yaw) offset = (-turned.y, turned.x, 0)
};

TurnedOffset turnedOffset(const CollisionCentre& centre, const double* x, int dimension) {
  TurnedOffset result;
  result.inverse_radius = 1.0 / centre.turning_radius;
  const double yaw = x[centre.index + dimension] * result.inverse_radius;
  const double c = std::cos(yaw), s = std::sin(yaw);
  const Eigen::Vector3d& o = centre.offset;
  result.turned = Eigen::Vector3d(c * o.x() - s * o.y(), s * o.x() + c * o.y(), o.z());
  result.normal = Eigen::Vector3d(-result.turned.y(), result.turned.x(), 0.0);
  return result;
}

}  // namespace

std::vector<int> CentreEvaluator::variables(const CollisionCentre& centre) const {
  if (centre.source == CollisionCentre::Source::kRobotSphere) return robot_->chainOf(centre.index);
  std::vector<int> result;
  for (int d = 0; d < dimension_; ++d) result.push_back(centre.index + d);
  if (centre.source == CollisionCentre::Source::kTurningBody) {
    result.push_back(centre.index + dimension_);
  }
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
  const Eigen::Vector3d offset = centre.source == CollisionCentre::Source::kTurningBody
                                     ? turnedOffset(centre, free_state_, dimension_).turned
                                     : centre.offset;
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  for (int d = 0; d < dimension_; ++d) p(d) = free_state_[centre.index + d] + offset(d);
  return p;
}

void CentreEvaluator::jacobian(const CollisionCentre& centre, Eigen::Matrix3Xd& into) const {
  if (centre.source != CollisionCentre::Source::kRobotSphere) {
    const int n = dimension_ + (centre.source == CollisionCentre::Source::kTurningBody ? 1 : 0);
    into.setZero(3, n);
    for (int d = 0; d < dimension_; ++d) into(d, d) = 1.0;
    if (n > dimension_) {
      const TurnedOffset t = turnedOffset(centre, free_state_, dimension_);
      into.col(dimension_) = inPlane(t.normal * t.inverse_radius);
    }
    return;
  }
  into = sphereDerivatives(centre.index).jacobian();
  if (dimension_ == 2) into.row(2).setZero();
}

void CentreEvaluator::weightedHessian(const CollisionCentre& centre, const Eigen::Vector3d& w,
                                      Eigen::MatrixXd& into) const {
  if (centre.source != CollisionCentre::Source::kRobotSphere) {
    const int n = dimension_ + (centre.source == CollisionCentre::Source::kTurningBody ? 1 : 0);
    into.setZero(n, n);
    if (n > dimension_) {  // only the turn enters nonlinearly: d2/ds2 R offset = -R offset / rho^2
      const TurnedOffset t = turnedOffset(centre, free_state_, dimension_);
      const Eigen::Vector3d planar(t.turned.x(), t.turned.y(), 0.0);
      into(dimension_, dimension_) = -inPlane(w).dot(planar) * t.inverse_radius * t.inverse_radius;
    }
    return;
  }
  sphereDerivatives(centre.index).weightedHessian(inPlane(w), into);
}

void CentreEvaluator::weightedThirdDerivative(const CollisionCentre& centre,
                                              const Eigen::Vector3d& w, const Eigen::VectorXd& v,
                                              Eigen::MatrixXd& into) const {
  if (centre.source != CollisionCentre::Source::kRobotSphere) {
    const int n = dimension_ + (centre.source == CollisionCentre::Source::kTurningBody ? 1 : 0);
    into.setZero(n, n);
    if (n > dimension_) {  // d3/ds3 R offset = -(dR/dyaw) offset / rho^3
      const TurnedOffset t = turnedOffset(centre, free_state_, dimension_);
      into(dimension_, dimension_) = -inPlane(w).dot(t.normal) * t.inverse_radius *
                                     t.inverse_radius * t.inverse_radius * v(dimension_);
    }
    return;
  }
  sphereDerivatives(centre.index).weightedThirdDerivative(inPlane(w), v, into);
}

}  // namespace fesd
