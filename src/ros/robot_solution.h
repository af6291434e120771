#pragma once

#include <string>

#include <fesd_trajopt/Solution.h>
#include <visualization_msgs/MarkerArray.h>

#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd_ros {

// The robot's part of an answer (sceneSolution, sceneMarkers call them for a scene with a robot).

/// joint_trajectory (positions and actual velocities at the element boundaries) and
/// joint_commands (the commanded joint velocities per control interval).
void addJointTrajectories(const fesd::SceneTask& task, const fesd::SceneOutcome& outcome,
                          fesd_trajopt::Solution& solution);

/// The markers fitted to a robot's scale and the robot's spheres at the start (robot_start), the
/// end (robot_final) and every switch (robot_switch_configurations).
void addRobotMarkers(const fesd::SceneTask& task, const fesd_trajopt::Solution& solution,
                     const std::string& frame_id, visualization_msgs::MarkerArray& markers);

}  // namespace fesd_ros
