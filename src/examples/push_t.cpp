#include "fesd_trajopt/examples/push_t.h"

#include <cmath>
#include <string>

#include "fesd_trajopt/examples/seeded_random.h"

namespace fesd {
namespace push_t {

SceneBody tBlock(const Eigen::Vector2d& position, double yaw, double width) {
  SceneBody t{"t_block", 0.5 * width, Eigen::Vector2d::Zero()};
  const auto add = [&](double x, double y) {
    t.spheres.push_back({"t_block/sphere_" + std::to_string(t.spheres.size()),
                         Eigen::Vector3d(x, y, 0.0), 0.5 * width});
  };
  for (int k = -3; k <= 3; ++k) add(0.5 * width * k, 0.0);  // the bar, 4 w long
  for (int k = 2; k <= 6; ++k) add(0.0, -0.5 * width * k);  // the stem, 3 w below the bar
  t.yaw = yaw;
  turnAboutPressureCentre(t);
  t.position = position;  // the centre of pressure, where the T is placed
  return t;
}

Eigen::Vector2d targetPosition() {
  return Eigen::Vector2d::Zero();
}

double targetYaw() {
  return M_PI / 4.0;
}

SceneTask task(const Eigen::Vector2d& position, double yaw, const Eigen::Vector2d& pusher,
               double horizon, int intervals) {
  const double width = 0.5;
  SceneTask task;
  task.scene.bodies() = {{"pusher", 0.5 * width, pusher, true}, tBlock(position, yaw, width)};
  task.bodies.resize(2);
  task.bodies[0].max_speed = 2.0;
  task.bodies[1].target = targetPosition();
  task.bodies[1].target_weight = 100.0;
  // The T has no symmetry: the target's equivalent nearest the start, at most half a turn away.
  task.bodies[1].target_yaw = yaw + std::remainder(targetYaw() - yaw, 2.0 * M_PI);
  task.bodies[1].target_yaw_weight = 100.0;
  task.horizon = horizon;
  task.num_intervals = intervals;
  return task;
}

SceneTask randomStart(unsigned seed) {
  SeededUniform random(seed);
  const Eigen::Vector2d position = std::sqrt(random()) * 2.5 * random.unitVector(2);
  const double yaw = random(-M_PI, M_PI);
  const Eigen::Vector2d pusher = position + random(2.5, 4.0) * random.unitVector(2);
  return task(position, yaw, pusher);
}

}  // namespace push_t
}  // namespace fesd
