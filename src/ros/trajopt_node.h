#pragma once

#include <map>
#include <mutex>
#include <string>

#include <fesd_trajopt/Simulate.h>
#include <fesd_trajopt/SolveTrajectory.h>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "node_config.h"

namespace fesd_ros {

/// The fesd_trajopt node: ~solve_trajectory and ~simulate services; latched ~markers
/// (visualization_msgs/MarkerArray), ~solution (fesd_trajopt/Solution) and ~paths/<body>
/// (nav_msgs/Path) topics; a static transform that makes ~frame_id exist for rviz. Requests are
/// served concurrently, each with its own solver; their Ipopt solves take turns (the core
/// serialises them, MUMPS not being thread-safe).
class TrajoptNode {
 public:
  TrajoptNode(ros::NodeHandle node, ros::NodeHandle private_node);

 private:
  bool solveTrajectory(fesd_trajopt::SolveTrajectory::Request& request,
                       fesd_trajopt::SolveTrajectory::Response& response);
  bool simulate(fesd_trajopt::Simulate::Request& request,
                fesd_trajopt::Simulate::Response& response);
  void handleSolve(const fesd_trajopt::SolveTrajectory::Request& request,
                   fesd_trajopt::SolveTrajectory::Response& response);
  void handleSimulate(const fesd_trajopt::Simulate::Request& request,
                      fesd_trajopt::Simulate::Response& response);

  ros::NodeHandle node_, private_node_;
  NodeConfig config_;
  ros::ServiceServer solve_service_, simulate_service_;
  ros::Publisher marker_publisher_, solution_publisher_;
  std::map<std::string, ros::Publisher> path_publishers_;  ///< by body name, latched
  tf2_ros::StaticTransformBroadcaster frame_broadcaster_;
  std::mutex publish_mutex_;
};

}  // namespace fesd_ros
