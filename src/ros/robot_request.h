#pragma once

#include <string>
#include <vector>

#include <fesd_trajopt/JointSpec.h>
#include <ros/node_handle.h>

#include "fesd_trajopt/scene/robot_from_urdf.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd_ros {

/// The robot-only fields of a request.
struct RobotFields {
  std::vector<fesd_trajopt::JointSpec> joints;
  bool self_collision = false;
  std::string srdf_param;
};

/// Whether a URDF describes a robot: it has revolute, continuous or prismatic joints. Other
/// URDFs (or ones that do not parse) are disc scenes (sceneFromUrdf), which report their errors.
bool isRobotUrdf(const std::string& urdf_xml);

/// The robot read from its URDF put into the task's scene (its free bodies already there) with
/// the request's joint settings, self-collision and SRDF: joint names, roles and numbers are
/// checked here, the rest (bounds excluding the start, overlaps, sizes) by validateTask. Returns
/// "" or why not.
std::string applyRobotFields(const fesd::RobotForScene& read, const RobotFields& robot,
                             const ros::NodeHandle& node, fesd::SceneTask& task);

}  // namespace fesd_ros
