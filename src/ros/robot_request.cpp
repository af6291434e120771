#include "robot_request.h"

#include <cmath>

#include <fesd_trajopt/BodySpec.h>

#include "fesd_trajopt/kinematics/srdf.h"

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
/// validateTask checks the rest (contradictory bounds, a start outside them).
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

}  // namespace

bool isRobotUrdf(const std::string& urdf_xml) {
  const fesd::KinematicModelResult read = fesd::buildKinematicModel(urdf_xml);
  return read.error.empty() && read.model.numCoordinates() > 0;
}

std::string applyRobotFields(const fesd::RobotForScene& read, const RobotFields& robot,
                             const ros::NodeHandle& node, fesd::SceneTask& task) {
  const int joints = read.robot->numCoordinates();
  Eigen::VectorXd start = Eigen::VectorXd::Zero(joints);
  task.joints.assign(joints, fesd::JointTask{});
  for (const fesd_trajopt::JointSpec& spec : robot.joints) {
    const int j = read.robot->jointIndex(spec.name);
    if (j < 0) {
      return "joint '" + spec.name +
             "' is not a moving joint of the robot (its joints: " + jointNames(*read.robot) + ")";
    }
    const std::string problem = applyJointSpec(spec, task.joints[j], start(j));
    if (!problem.empty()) return problem;
  }
  task.scene.setRobot(read.robot, start);
  task.scene.self_collision = robot.self_collision;
  if (robot.srdf_param.empty()) return "";
  std::string srdf;
  if (!node.getParam(robot.srdf_param, srdf) &&
      !ros::NodeHandle().getParam(robot.srdf_param, srdf)) {
    return "no parameter '" + robot.srdf_param + "' holds an SRDF";
  }
  const fesd::SrdfDisabledCollisions disabled = fesd::disabledCollisionsFromSrdf(srdf);
  if (!disabled.error.empty()) return "SRDF '" + robot.srdf_param + "': " + disabled.error;
  task.scene.disabled_link_pairs = disabled.pairs;
  return "";
}

}  // namespace fesd_ros
