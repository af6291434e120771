#include "fesd_trajopt/scene/scene_units.h"

#include <algorithm>
#include <memory>
#include <vector>

#include "fesd_trajopt/kinematics/model_units.h"

namespace fesd {
namespace {

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const size_t n = values.size();
  return n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

void scaleIfSet(Eigen::VectorXd& v, double factor) {
  if (v.size()) v *= factor;
}

/// The scene with its free bodies, obstacles and walls scaled by `factor` and the robot
/// given (its joints' start with it), or none.
Scene scaledScene(const Scene& scene, double factor, std::shared_ptr<const KinematicModel> robot,
                  const Eigen::VectorXd& q0) {
  Scene scaled = scene;
  for (SceneBody& body : scaled.bodies()) {
    body.radius *= factor;
    body.position *= factor;
    body.turning_radius *= factor;
    for (FreeBodySphere& sphere : body.spheres) {
      sphere.offset *= factor;
      sphere.radius *= factor;
    }
  }
  for (SceneObstacle& obstacle : scaled.obstacles()) {
    obstacle.radius *= factor;
    obstacle.position *= factor;
  }
  for (SceneWall& wall : scaled.walls()) wall.offset *= factor;
  if (robot) scaled.setRobot(std::move(robot), q0);
  return scaled;
}

void scaleBodyTasks(std::vector<BodyTask>& bodies, double factor) {
  for (BodyTask& body : bodies) {
    body.max_speed *= factor;
    scaleIfSet(body.target, factor);
    scaleIfSet(body.workspace_lower, factor);
    scaleIfSet(body.workspace_upper, factor);
    body.target_yaw_weight *= factor * factor;
  }
}

void scaleJointTask(JointTask& joint, double factor) {
  joint.max_velocity *= factor;
  joint.target *= factor;
  joint.lower *= factor;
  joint.upper *= factor;
}

}  // namespace

double lengthScale(const SceneTask& task) {
  const Scene& scene = task.scene;
  std::vector<double> driven, free;
  for (const CollisionBody& body : scene.collisionBodies()) {
    if (body.free_body >= 0) {
      free.push_back(body.radius);
      if (scene.bodies()[body.free_body].actuated) driven.push_back(body.radius);
    } else if (scene.robot().links[scene.robot().spheres[body.sphere].link].joint >= 0) {
      driven.push_back(body.radius);
    }
  }
  if (!driven.empty()) return median(driven);
  return free.empty() ? 1.0 : median(free);
}

SceneTask scaledTask(const SceneTask& task, double factor) {
  SceneTask scaled = task;
  const Scene& scene = task.scene;
  std::shared_ptr<const KinematicModel> robot;
  Eigen::VectorXd q0 = scene.initialJoints();
  if (scene.hasRobot()) {
    robot = std::make_shared<const KinematicModel>(withLengthsScaled(scene.robot(), factor));
    for (int j = 0; j < scene.numJoints(); ++j) {
      JointTask& joint = scaled.joints[j];
      if (scene.robot().joints[j].type == JointType::kPrismatic) {
        q0(j) *= factor;
        scaleJointTask(joint, factor);
      } else {
        joint.target_weight *= factor * factor;
      }
    }
  }
  scaled.scene = scaledScene(scene, factor, robot, q0);
  scaleBodyTasks(scaled.bodies, factor);
  return scaled;
}

SceneTask taskInLengthUnits(const SceneTask& task, double length_scale) {
  const double factor = 1.0 / length_scale;
  SceneTask scaled = task;
  const Scene& scene = task.scene;
  std::shared_ptr<const KinematicModel> robot;
  if (scene.hasRobot()) {
    robot = std::make_shared<const KinematicModel>(inLengthUnits(scene.robot(), length_scale));
    for (JointTask& joint : scaled.joints) scaleJointTask(joint, factor);
    scaled.default_joint_velocity *= factor;
  }
  scaled.scene = scaledScene(scene, factor, robot, scene.initialJoints() * factor);
  scaleBodyTasks(scaled.bodies, factor);
  scaled.scene.length_unit = scene.length_unit * length_scale;
  return scaled;
}

}  // namespace fesd
