#include "fesd_trajopt/scene/scene_units.h"

#include <algorithm>
#include <cmath>
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

/// The joint tasks and start of a robot in a solve's units (coordinates over their units): speeds
/// made explicit where the task's default would have applied, target weights such that each
/// target's cost is the task's over length_scale^2.
void jointsInUnits(const SceneTask& task, const Scene& solve_scene, double length_scale,
                   std::vector<JointTask>& joints, Eigen::VectorXd& q0) {
  for (int j = 0; j < solve_scene.numJoints(); ++j) {
    JointTask& joint = joints[j];
    const double unit = solve_scene.jointUnit(j);
    if (!joint.passive && !(joint.max_velocity > 0.0) &&
        !(task.scene.robot().joints[j].max_velocity > 0.0)) {
      joint.max_velocity = task.default_joint_velocity;
    }
    scaleJointTask(joint, 1.0 / unit);
    joint.target_weight *= unit * unit / (length_scale * length_scale);
    q0(j) /= unit;
  }
}

}  // namespace

double lengthScale(const SceneTask& task) {
  const Scene& scene = task.scene;
  // A sphere the robot's commands move: on a chain with a joint that is not passive.
  const auto commanded = [&](int sphere) {
    const std::vector<int>& chain = scene.robot().chainOf(sphere);
    return std::any_of(chain.begin(), chain.end(), [&](int j) {
      return j >= static_cast<int>(task.joints.size()) || !task.joints[j].passive;
    });
  };
  std::vector<double> driven, free;
  for (const CollisionBody& body : scene.collisionBodies()) {
    if (body.free_body >= 0) {
      free.push_back(body.radius);
      if (scene.bodies()[body.free_body].actuated) driven.push_back(body.radius);
    } else if (commanded(body.sphere)) {
      driven.push_back(body.radius);
    }
  }
  const double length = !driven.empty() ? median(driven) : free.empty() ? 1.0 : median(free);
  // A task with a radius that is not positive or finite is refused as it is (validateTask).
  return length > 0.0 && std::isfinite(length) ? length : 1.0;
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
  }
  scaled.scene = scaledScene(scene, factor, robot, scene.initialJoints());
  scaled.scene.length_unit = scene.length_unit * length_scale;
  if (robot) {
    Eigen::VectorXd q0 = scene.initialJoints();
    jointsInUnits(task, scaled.scene, length_scale, scaled.joints, q0);
    scaled.scene.setRobot(robot, q0);
    scaled.default_joint_velocity *= factor;  // every joint's speed is explicit
  }
  scaleBodyTasks(scaled.bodies, factor);
  return scaled;
}

SolveUnits solveUnits(const Scene& solve_scene) {
  SolveUnits units;
  units.length = solve_scene.length_unit;
  units.state = Eigen::VectorXd::Constant(solve_scene.stateSize(), units.length);
  units.control = Eigen::VectorXd::Constant(solve_scene.controlSize(), units.length);
  for (int j = 0; j < solve_scene.numJoints(); ++j) {
    units.state(j) = units.control(j) = solve_scene.jointUnit(j);
  }
  return units;
}

}  // namespace fesd
