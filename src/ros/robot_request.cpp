#include "robot_request.h"

#include <cmath>
#include <limits>
#include <memory>

#include <fesd_trajopt/BodySpec.h>

#include "fesd_trajopt/kinematics/srdf.h"
#include "fesd_trajopt/scene/robot_from_urdf.h"

namespace fesd_ros {
namespace {

std::string jointNames(const fesd::KinematicModel& robot) {
  std::string names;
  for (const fesd::KinematicJoint& joint : robot.joints) {
    names += (names.empty() ? "" : ", ") + joint.name;
  }
  return names;
}

/// One JointSpec applied to its joint's task and start; returns "" or why it is refused. NaN is
/// refused here because a NaN max_velocity or weight would otherwise read as "not given";
/// validateRobotTask checks the rest (contradictory bounds, a start outside them).
std::string applyJointSpec(const fesd_trajopt::JointSpec& spec, fesd::JointTask& joint,
                           double& start) {
  const std::string who = "joint '" + spec.name + "'";
  joint.passive = spec.role == fesd_trajopt::BodySpec::ROLE_PASSIVE;
  if (joint.passive && spec.max_velocity != 0.0) {
    return who + " is passive: it takes no max_velocity (it moves only when pushed)";
  }
  if (spec.role > fesd_trajopt::BodySpec::ROLE_PASSIVE) {
    return who + " has an unknown role " + std::to_string(spec.role);
  }
  for (const double value : {spec.max_velocity, spec.initial_position, spec.target,
                             spec.target_weight, spec.lower, spec.upper}) {
    if (std::isnan(value)) return who + " has a NaN value";
  }
  if (spec.max_velocity < 0.0) return who + ": max_velocity must be >= 0 (0: the URDF's)";
  if (spec.target_weight < 0.0) return who + ": target_weight must be >= 0";
  if (spec.max_velocity > 0.0) joint.max_velocity = spec.max_velocity;
  if (spec.has_initial_position) start = spec.initial_position;
  if (spec.target_weight > 0.0) {
    joint.target = spec.target;
    joint.target_weight = spec.target_weight;
  }
  if (spec.has_bounds) {
    joint.has_bounds = true;
    joint.lower = spec.lower;
    joint.upper = spec.upper;
  }
  return "";
}

/// The request's allowed_pairs as the task's; "" or why not.
std::string allowPairs(const std::vector<fesd_trajopt::ContactPair>& allowed,
                       fesd::RobotTask& task) {
  const std::vector<fesd::RobotPair> all = task.scene.allPairs();
  for (const fesd_trajopt::ContactPair& entry : allowed) {
    bool found = false;
    for (const fesd::RobotPair& pair : all) {
      const auto [a, b] = task.scene.pairSides(pair);
      if ((fesd::namesSide(entry.first, a) && fesd::namesSide(entry.second, b)) ||
          (fesd::namesSide(entry.second, a) && fesd::namesSide(entry.first, b))) {
        task.allowed_pairs.push_back(pair);
        found = true;
      }
    }
    if (!found) {
      return "allowed pair " + entry.first + "/" + entry.second +
             " names no pair of the scene (unknown name, two fixed items, or spheres that never "
             "pair)";
    }
  }
  return "";
}

}  // namespace

bool isRobotUrdf(const std::string& urdf_xml) {
  const fesd::KinematicModelResult read = fesd::buildKinematicModel(urdf_xml);
  return read.error.empty() && read.model.numCoordinates() > 0;
}

RobotTaskBuild buildRobotTask(const NodeConfig& config, const SceneFields& scene,
                              const RobotFields& robot, const std::string& urdf_xml,
                              const ros::NodeHandle& node) {
  RobotTaskBuild build;
  const fesd::PlanarChoice choice = !scene.planar_override ? fesd::PlanarChoice::kInferred
                                    : scene.planar         ? fesd::PlanarChoice::kPlanar
                                                           : fesd::PlanarChoice::kSpatial;
  fesd::KinematicModelOptions limits;
  limits.max_spheres = config.limits.max_spheres;
  const fesd::RobotForScene read = fesd::robotForScene(urdf_xml, choice, limits);
  if (!read.error.empty()) {
    build.error = read.error;
    return build;
  }
  for (const std::string& shape : read.robot->ignored_shapes) {
    build.notes.push_back("collision " + shape + " is not a sphere and is ignored");
  }
  // The objects and obstacles come from the request, configured like a disc scene's.
  fesd::SceneTask objects;
  objects.scene = fesd::DiscScene(read.dimension);
  objects.scene.bodies() = read.free_bodies;  // the URDF's pucks, configured like its discs
  build.error = applySceneFields(config, scene, objects);
  if (!build.error.empty()) return build;
  for (size_t b = 0; b < read.free_body_spheres.size(); ++b) {
    const std::string& link = read.free_bodies[b].name;
    for (const fesd_trajopt::BodySpec& spec : scene.bodies) {
      if (spec.name == link && spec.radius > 0.0 && !read.free_body_spheres[b].empty()) {
        build.error = "body '" + link + "' carries " +
                      std::to_string(read.free_body_spheres[b].size()) +
                      " collision spheres in the URDF: its size comes from them, not a radius";
        return build;
      }
    }
  }

  const int joints = read.robot->numCoordinates();
  Eigen::VectorXd start = Eigen::VectorXd::Zero(joints);
  std::vector<fesd::JointTask> joint_tasks(joints);
  for (const fesd_trajopt::JointSpec& spec : robot.joints) {
    const int j = read.robot->jointIndex(spec.name);
    if (j < 0) {
      build.error = "joint '" + spec.name +
                    "' is not a moving joint of the robot (its joints: " + jointNames(*read.robot) +
                    ")";
      return build;
    }
    build.error = applyJointSpec(spec, joint_tasks[j], start(j));
    if (!build.error.empty()) return build;
  }
  fesd::RobotScene robot_scene(read.robot, start, objects.scene, read.free_body_spheres);
  robot_scene.self_collision = robot.self_collision;
  if (!robot.srdf_param.empty()) {
    std::string srdf;
    if (!node.getParam(robot.srdf_param, srdf) &&
        !ros::NodeHandle().getParam(robot.srdf_param, srdf)) {
      build.error = "no parameter '" + robot.srdf_param + "' holds an SRDF";
      return build;
    }
    const fesd::SrdfDisabledCollisions disabled = fesd::disabledCollisionsFromSrdf(srdf);
    if (!disabled.error.empty()) {
      build.error = "SRDF '" + robot.srdf_param + "': " + disabled.error;
      return build;
    }
    robot_scene.disabled_link_pairs = disabled.pairs;
  }
  fesd::RobotTask& task = build.task.emplace(std::move(robot_scene));
  task.joints = joint_tasks;
  task.bodies = objects.bodies;
  build.error = allowPairs(scene.allowed_pairs, task);
  if (!build.error.empty()) return build;
  // applySceneFields writes "no bounds" as +-infinity; a robot task wants none at all (finite
  // ones are refused by validateRobotTask, naming the body).
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (fesd::BodyTask& body : task.bodies) {
    if ((body.workspace_lower.array() == -kInf).all()) body.workspace_lower.resize(0);
    if ((body.workspace_upper.array() == kInf).all()) body.workspace_upper.resize(0);
  }
  return build;
}

}  // namespace fesd_ros
