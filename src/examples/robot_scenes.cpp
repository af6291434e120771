#include "fesd_trajopt/examples/robot_scenes.h"

#include <string>

namespace fesd {

SceneTask planarArmPushTask(std::shared_ptr<const KinematicModel> arm) {
  Scene discs(2);
  discs.bodies().push_back({"disc", 0.05, Eigen::Vector2d(0.6, 0.0), false});
  const Eigen::Vector3d q0(-0.6, 0.0, 0.0);
  SceneTask task = taskOn(robotInScene(std::move(arm), q0, discs));
  task.bodies[0].target = Eigen::Vector2d(0.6, 0.2);
  task.bodies[0].target_weight = 100.0;
  task.horizon = 2.0;
  task.num_intervals = 10;
  return task;
}

namespace {

/// The Panda at its ready pose with `body` on the table z >= 0, to be brought to `target`
/// (weight 100).
SceneTask pandaOnTheTable(std::shared_ptr<const KinematicModel> panda, const SceneBody& body,
                          const Eigen::Vector3d& target) {
  Scene table(3);
  table.bodies().push_back(body);
  table.walls().push_back({"table", Eigen::Vector3d(0.0, 0.0, 1.0), 0.0});
  const Eigen::VectorXd ready =
      (Eigen::VectorXd(7) << 0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785).finished();
  SceneTask task = taskOn(robotInScene(std::move(panda), ready, table));
  task.bodies[0].target = target;
  task.bodies[0].target_weight = 100.0;
  return task;
}

}  // namespace

SceneTask pandaPushTask(std::shared_ptr<const KinematicModel> panda) {
  SceneTask task =
      pandaOnTheTable(std::move(panda), {"puck", 0.05, Eigen::Vector3d(0.45, 0.0, 0.05), false},
                      Eigen::Vector3d(0.65, 0.0, 0.05));
  task.horizon = 2.0;
  // One contact and a straight 0.2 m push need few controls: 10 intervals took 1140 Ipopt
  // iterations (79x the showcase's wall time), 5 take 421 (bench robot-push).
  task.num_intervals = 5;
  return task;
}

SceneTask pandaSmallPuckTask(std::shared_ptr<const KinematicModel> panda) {
  SceneTask task = pandaPushTask(std::move(panda));
  task.scene.bodies()[0].radius = 0.02;
  task.scene.bodies()[0].position.z() = 0.02;
  task.bodies[0].target.z() = 0.02;
  return task;
}

SceneTask ur3ePushTask(std::shared_ptr<const KinematicModel> ur3e) {
  Scene table(3);
  table.bodies().push_back({"puck", 0.03, Eigen::Vector3d(-0.3, 0.1, 0.03), false});
  table.walls().push_back({"table", Eigen::Vector3d(0.0, 0.0, 1.0), 0.0});
  const Eigen::VectorXd q0 =
      (Eigen::VectorXd(6) << -0.91, -0.98, 1.52, -1.95, -1.92, 0.0).finished();
  SceneTask task = taskOn(robotInScene(std::move(ur3e), q0, table));
  task.bodies[0].target = Eigen::Vector3d(-0.3, -0.1, 0.03);
  task.bodies[0].target_weight = 100.0;
  task.horizon = 2.0;
  task.num_intervals = 8;
  return task;
}

SceneTask planarIiwaPushTask(std::shared_ptr<const KinematicModel> iiwa) {
  Scene discs(2);
  discs.bodies().push_back({"disc", 0.04, Eigen::Vector2d(0.75, 0.0), false});
  SceneTask task = taskOn(robotInScene(std::move(iiwa), Eigen::Vector3d(-0.6, 0.0, 0.0), discs));
  task.bodies[0].target = Eigen::Vector2d(0.75, 0.2);
  task.bodies[0].target_weight = 100.0;
  task.horizon = 2.0;
  task.num_intervals = 10;
  return task;
}

SceneTask pandaBarTask(std::shared_ptr<const KinematicModel> panda) {
  SceneBody bar{"bar", 0.03, Eigen::Vector3d(0.45, 0.0, 0.03)};
  for (int k = 0; k < 3; ++k) {
    bar.spheres.push_back(
        {"bar/sphere_" + std::to_string(k), Eigen::Vector3d(0.05 * (k - 1), 0.0, 0.0), 0.03});
  }
  bar.turns = true;
  turnAboutPressureCentre(bar);
  SceneTask task = pandaOnTheTable(std::move(panda), bar, Eigen::Vector3d(0.55, 0.07, 0.03));
  task.bodies[0].target_yaw = 0.5;
  task.bodies[0].target_yaw_weight = 100.0;
  task.horizon = 3.0;
  task.num_intervals = 12;
  return task;
}

}  // namespace fesd
