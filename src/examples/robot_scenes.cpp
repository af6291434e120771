#include "fesd_trajopt/examples/robot_scenes.h"

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

SceneTask pandaPushTask(std::shared_ptr<const KinematicModel> panda) {
  Scene discs(3);
  discs.bodies().push_back({"puck", 0.05, Eigen::Vector3d(0.45, 0.0, 0.05), false});
  discs.walls().push_back({"table", Eigen::Vector3d(0.0, 0.0, 1.0), 0.0});
  const Eigen::VectorXd ready =
      (Eigen::VectorXd(7) << 0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785).finished();
  SceneTask task = taskOn(robotInScene(std::move(panda), ready, discs));
  task.bodies[0].target = Eigen::Vector3d(0.65, 0.0, 0.05);
  task.bodies[0].target_weight = 100.0;
  task.horizon = 2.0;
  // One contact and a straight 0.2 m push need few controls: 10 intervals took 1140 Ipopt
  // iterations (79x the showcase's wall time), 5 take 421 (bench robot-push).
  task.num_intervals = 5;
  return task;
}

}  // namespace fesd
