#pragma once

#include <fesd_trajopt/Solution.h>
#include <visualization_msgs/MarkerArray.h>

#include "fesd_trajopt/scene/robot_solver.h"
#include "fesd_trajopt/scene/robot_task.h"

namespace fesd_ros {

/// The Solution message of a robot task's outcome: as sceneSolution for the free bodies, plus
/// joint_trajectory (positions and actual velocities at the element boundaries), joint_commands
/// (the commanded joint velocities per control interval) and switches and pairs named by the
/// robot's spheres (`<link>/sphere_<k>`).
fesd_trajopt::Solution robotSolution(const fesd::RobotTask& task,
                                     const fesd::RobotOutcome& outcome);

/// sceneMarkers of the free bodies plus the robot's spheres at the start (robot_start), the end
/// (robot_final) and every switch (robot_switch_configurations).
visualization_msgs::MarkerArray robotMarkers(const fesd::RobotTask& task,
                                             const fesd_trajopt::Solution& solution,
                                             const std::string& frame_id);

}  // namespace fesd_ros
