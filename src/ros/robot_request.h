#pragma once

#include <optional>
#include <string>
#include <vector>

#include <fesd_trajopt/JointSpec.h>
#include <ros/node_handle.h>

#include "fesd_trajopt/scene/robot_task.h"
#include "node_config.h"
#include "scene_request.h"

namespace fesd_ros {

/// The robot-only fields of a request.
struct RobotFields {
  std::vector<fesd_trajopt::JointSpec> joints;
  bool self_collision = false;
  std::string srdf_param;
};

/// A robot task built from a request, or why not (error non-empty).
struct RobotTaskBuild {
  std::optional<fesd::RobotTask> task;
  std::string error;
  std::vector<std::string> notes;  ///< e.g. collision shapes that were ignored
};

/// Whether a URDF describes a robot: it has revolute, continuous or prismatic joints. Other
/// URDFs (or ones that do not parse) are disc scenes, whose path reports their errors.
bool isRobotUrdf(const std::string& urdf_xml);

/// The robot of `urdf_xml` (planar inferred unless the request forces it) in a scene of the
/// request's added bodies, obstacles and walls, with the configured horizon, intervals and
/// control weight and the request's joint settings. Joint names, roles and numbers are checked
/// here; the rest (bounds excluding the start, overlaps, sizes) by validateRobotTask.
RobotTaskBuild buildRobotTask(const NodeConfig& config, const SceneFields& scene,
                              const RobotFields& robot, const std::string& urdf_xml,
                              const ros::NodeHandle& node);

}  // namespace fesd_ros
