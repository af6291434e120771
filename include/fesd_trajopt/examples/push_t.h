#pragma once

#include <Eigen/Dense>

#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// Push-T (Chi et al. 2023's benchmark) in our units: one disc pusher brings a T-shaped block
/// that turns to a pose on an open table.
namespace push_t {

/// The T of width w: a top bar 4 w long and w wide, a stem of the same width 3 w long below its
/// middle, filled with spheres of radius w / 2 along their centre lines every w / 2 (7 in the
/// bar, 5 in the stem), turning about its centre of pressure (at `position`, yaw `yaw`).
SceneBody tBlock(const Eigen::Vector2d& position, double yaw, double width = 0.5);

/// The benchmark's target pose: the T's centre of pressure at the origin, yaw pi / 4.
Eigen::Vector2d targetPosition();
double targetYaw();

/// The T at (position, yaw), the pusher (radius w / 2, |u| <= 2 per coordinate) at `pusher`,
/// to the target pose (weights 100; the target yaw the equivalent of pi / 4 nearest the start)
/// in `horizon` on `intervals` control intervals.
SceneTask task(const Eigen::Vector2d& position, double yaw, const Eigen::Vector2d& pusher,
               double horizon = 10.0, int intervals = 40);

/// Start `seed` of the benchmark: the T's centre within 2.5 of the target (half of a 10 x 10
/// table) at any yaw, the pusher 2.5 to 4 from the T's centre in any direction (clear of it).
SceneTask randomStart(unsigned seed);

}  // namespace push_t
}  // namespace fesd
