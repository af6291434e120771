#pragma once

#include <string>

#include <Eigen/Dense>

#include "fesd_trajopt/scene/scene_task.h"

namespace fesd_ros {

/// Where a body's target may be dragged to: inside its workspace bounds and within `reach` of
/// the scene's centre (so that a pose of 1e12 is refused for a body without bounds too).
struct TargetRegion {
  int dimension = 2;  ///< 2: planar (x, y); 3: spatial, the target's height kept (on its table)
  Eigen::VectorXd lower, upper;  ///< the workspace bounds per coordinate; empty: none
  Eigen::Vector3d centre = Eigen::Vector3d::Zero();
  double reach = 0.0;
};

/// A dragged pose as a target, or why it is refused.
struct TargetPlacement {
  std::string refused;       ///< "" when the pose is a target
  Eigen::VectorXd position;  ///< in the scene's coordinates (x, y[, z])
  double yaw = 0.0;  ///< about z, the nearest to the previous yaw (continuous, not mod 2 pi)
};

/// Scene sizes about the scene's centre a target may be dragged to.
constexpr double kTargetReachInSceneSizes = 10.0;

/// The region of body `b` of a task: its bounds and kTargetReachInSceneSizes times the extent of
/// what the scene holds (bodies, their targets and obstacles) about its centre.
TargetRegion targetRegion(const fesd::SceneTask& task, int b);

/// The pose (position; orientation as a quaternion x, y, z, w) dragged to as a target of a body in
/// `region`: planar scenes take x and y, spatial ones x and y at `height`; refused when not
/// finite, outside the bounds or beyond the reach. The yaw is unwrapped next to `previous_yaw`.
TargetPlacement placeTarget(const TargetRegion& region, const Eigen::Vector3d& position,
                            const Eigen::Vector4d& quaternion, double height, double previous_yaw);

}  // namespace fesd_ros
