#include "support/scene_tasks.h"

namespace fesd_test {

fesd::SceneTask pushingTask() {
  fesd::SceneTask task;
  task.scene.bodies() = {{"pusher", 0.5, Eigen::Vector2d(-3.0, 0.0), true},
                         {"puck", 0.5, Eigen::Vector2d(0.0, 0.0), false},
                         {"rock", 1.0, Eigen::Vector2d(100.0, 100.0), false}};
  task.bodies.resize(3);
  task.bodies[0].max_speed = 2.0;
  task.horizon = 2.0;
  task.num_intervals = 4;
  return task;
}

fesd::SceneTask pushingTaskWithPost() {
  fesd::SceneTask task = pushingTask();
  task.scene.obstacles() = {{"post", 0.4, Eigen::Vector2d(0.0, 3.0)}};
  return task;
}

fesd::SceneTask slowPushingTask() {
  fesd::SceneTask task = pushingTask();
  task.scene.bodies()[2] = {"rock", 0.5, Eigen::Vector2d(50.0, 0.0), false};
  task.bodies[0].max_speed = 1.0;
  return task;
}

fesd::SceneTask pushAlongX() {
  fesd::SceneTask task;
  task.scene.bodies() = {{"pusher", 0.5, Eigen::Vector2d(-2.0, 0.0), true},
                         {"puck", 0.5, Eigen::Vector2d(0.0, 0.0), false}};
  task.bodies.resize(2);
  task.bodies[0].max_speed = 4.0;
  task.bodies[1].target = Eigen::Vector2d(3.0, 0.0);
  task.bodies[1].target_weight = 100.0;
  task.horizon = 2.0;
  task.num_intervals = 20;
  return task;
}

fesd::SceneTask pushAlongAWall() {
  fesd::SceneTask task = pushAlongX();
  task.scene.bodies()[0].position = Eigen::Vector2d(-2.0, 0.3);
  task.scene.bodies()[1].radius = 0.3;
  task.scene.walls().push_back({"floor", Eigen::Vector2d(0.0, 1.0), -0.35});
  return task;
}

fesd::SceneTask boxIntoACorner() {
  fesd::SceneBody box{"box", 0.25, Eigen::Vector2d::Zero()};
  for (const auto& [x, y] : {std::pair{-0.25, -0.25}, {0.25, -0.25}, {-0.25, 0.25}, {0.25, 0.25}}) {
    box.spheres.push_back(
        {"box/sphere_" + std::to_string(box.spheres.size()), Eigen::Vector3d(x, y, 0.0), 0.25});
  }
  box.yaw = 0.3;
  fesd::turnAboutPressureCentre(box);
  fesd::SceneTask task;
  task.scene.bodies() = {{"pusher", 0.2, Eigen::Vector2d(-1.5, 0.2), true}, box};
  task.scene.walls() = {{"right", Eigen::Vector2d(-1.0, 0.0), -1.5},
                        {"floor", Eigen::Vector2d(0.0, 1.0), -1.0}};
  task.bodies.resize(2);
  task.bodies[0].max_speed = 2.0;
  task.bodies[1].target = Eigen::Vector2d(1.0, -0.5);
  task.bodies[1].target_weight = 100.0;
  task.bodies[1].target_yaw = 0.0;
  task.bodies[1].target_yaw_weight = 100.0;
  task.horizon = 4.0;
  task.num_intervals = 20;
  return task;
}

fesd::SceneTask puckOnATable(double pusher_height) {
  fesd::Scene scene(3);
  scene.bodies().push_back({"pusher", 0.03, Eigen::Vector3d(-0.2, 0.0, pusher_height), true});
  scene.bodies().push_back({"puck", 0.05, Eigen::Vector3d(0.0, 0.0, 0.05), false});
  scene.walls().push_back({"table", Eigen::Vector3d::UnitZ(), 0.0});
  fesd::SceneTask task = fesd::taskOn(scene);
  task.bodies[0].max_speed = 0.3;
  task.horizon = 2.0;
  task.num_intervals = 10;
  return task;
}

fesd::SceneSolveOptions nodeGridOptions() {
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 3;
  options.verification.num_stages = 3;
  options.verification.num_elements = 6;
  return options;
}

fesd::SceneSolveOptions robotSolveOptions() {
  fesd::SceneSolveOptions options;
  options.lazy_pairs = false;
  options.verify = true;
  return options;
}

}  // namespace fesd_test
