#include "target_region.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace fesd_ros {
namespace {

/// The angle a - b in (-pi, pi].
double angleBetween(double a, double b) {
  return std::remainder(a - b, 2.0 * M_PI);
}

}  // namespace

TargetRegion targetRegion(const fesd::SceneTask& task, int b) {
  const fesd::Scene& scene = task.scene;
  TargetRegion region;
  region.dimension = scene.dimension();
  region.lower = task.bodies[b].workspace_lower;
  region.upper = task.bodies[b].workspace_upper;
  Eigen::Vector3d low = Eigen::Vector3d::Constant(INFINITY), high = -low;
  double largest_radius = 0.0;
  auto include = [&](const Eigen::VectorXd& p, double radius) {
    Eigen::Vector3d point = Eigen::Vector3d::Zero(), extent = Eigen::Vector3d::Zero();
    point.head(p.size()) = p;
    extent.head(p.size()).setConstant(radius);  // a planar scene's z stays 0
    low = low.cwiseMin(point - extent);
    high = high.cwiseMax(point + extent);
    largest_radius = std::max(largest_radius, radius);
  };
  for (size_t i = 0; i < scene.bodies().size(); ++i) {
    include(scene.bodies()[i].position, scene.bodies()[i].radius);
    if (task.bodies[i].hasTarget()) include(task.bodies[i].target, scene.bodies()[i].radius);
  }
  for (const fesd::SceneObstacle& obstacle : scene.obstacles()) {
    include(obstacle.position, obstacle.radius);
  }
  region.centre = 0.5 * (low + high);
  region.reach = kTargetReachInSceneSizes * std::max(0.5 * (high - low).norm(), largest_radius);
  return region;
}

TargetPlacement placeTarget(const TargetRegion& region, const Eigen::Vector3d& position,
                            const Eigen::Vector4d& quaternion, double height, double previous_yaw) {
  TargetPlacement placement;
  if (!position.allFinite() || !quaternion.allFinite() || !(quaternion.norm() > 0.0)) {
    placement.refused = "the pose is not finite";
    return placement;
  }
  placement.position = position.head(region.dimension);
  if (region.dimension == 3) placement.position(2) = height;
  const Eigen::VectorXd& p = placement.position;
  std::ostringstream why;
  if ((region.lower.size() && (p.array() < region.lower.array()).any()) ||
      (region.upper.size() && (p.array() > region.upper.array()).any())) {
    why << "(" << p.transpose() << ") is outside the body's workspace bounds";
  } else {
    Eigen::Vector3d point = Eigen::Vector3d::Zero();
    point.head(p.size()) = p;
    const double distance = (point - region.centre).norm();
    if (distance > region.reach) {
      why << "(" << p.transpose() << ") is " << distance << " from the scene's centre, beyond "
          << region.reach << " (" << kTargetReachInSceneSizes << " scene sizes)";
    }
  }
  placement.refused = why.str();
  const Eigen::Vector4d q = quaternion.normalized();  // x, y, z, w
  const double yaw =
      std::atan2(2.0 * (q(3) * q(2) + q(0) * q(1)), 1.0 - 2.0 * (q(1) * q(1) + q(2) * q(2)));
  placement.yaw = previous_yaw + angleBetween(yaw, previous_yaw);
  return placement;
}

}  // namespace fesd_ros
