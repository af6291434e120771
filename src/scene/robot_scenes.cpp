#include "fesd_trajopt/scene/robot_scenes.h"

namespace fesd {

RobotTask planarArmPushTask(std::shared_ptr<const KinematicModel> arm) {
  DiscScene discs(2);
  discs.bodies().push_back({"disc", 0.05, Eigen::Vector2d(0.6, 0.0), false});
  const Eigen::Vector3d q0(-0.6, 0.0, 0.0);
  RobotTask task(RobotScene(std::move(arm), q0, discs));
  task.bodies[0].target = Eigen::Vector2d(0.6, 0.2);
  task.bodies[0].target_weight = 100.0;
  task.horizon = 2.0;
  task.num_intervals = 10;
  return task;
}

}  // namespace fesd
