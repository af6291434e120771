#include "fesd_trajopt/examples/manipulation_example.h"

#include <limits>

namespace fesd {
namespace manipulation_example {

SceneTask task(int num_intervals) {
  SceneTask task;
  task.scene.bodies() = {{"actuator_1", 1.0, Eigen::Vector2d(-10.0, 10.0), true},
                         {"actuator_2", 1.0, Eigen::Vector2d(5.0, -5.0), true},
                         {"object", 2.0, Eigen::Vector2d(0.0, 0.0), false}};
  const double inf = std::numeric_limits<double>::infinity();
  BodyTask actuator_1{10.0, Eigen::Vector2d(-10.0, 0.0), 1.0, {}, Eigen::Vector2d(-2.5, inf)};
  BodyTask actuator_2{10.0, Eigen::Vector2d(10.0, 0.0), 1.0, Eigen::Vector2d(2.5, -inf), {}};
  BodyTask object{0.0, Eigen::Vector2d(0.0, 10.0), 1e3, {}, {}};
  task.bodies = {actuator_1, actuator_2, object};
  task.horizon = 5.0;
  task.num_intervals = num_intervals;
  task.control_weight = 1e-4;
  return task;
}

SceneTask task(int num_intervals, const Eigen::Vector2d& object_goal) {
  SceneTask moved = task(num_intervals);
  moved.bodies[2].target = object_goal;
  return moved;
}

std::vector<ContactPair> contactPairs() {
  return {{0, ContactPair::Kind::kBody, 2}, {1, ContactPair::Kind::kBody, 2}};
}

Eigen::VectorXd targetState() {
  Eigen::VectorXd target(6);
  target << -10.0, 0.0, 10.0, 0.0, 0.0, 10.0;
  return target;
}

Eigen::Vector2d objectGoal() {
  return targetState().tail<2>();
}

OcpDefinition ocp(int num_intervals) {
  return buildOcp(task(num_intervals), contactPairs());
}

PushPlan plan(int num_intervals) {
  return planPushes(task(num_intervals), contactPairs());
}

}  // namespace manipulation_example
}  // namespace fesd
