#pragma once

#include <map>
#include <string>

#include <ros/node_handle.h>

#include "fesd_trajopt/scene/scene_task.h"
#include "fesd_trajopt/solver/mpcc_solver.h"

namespace fesd_ros {

/// Configured defaults of one body (by URDF link name).
struct BodyConfig {
  bool actuated = false;
  double max_speed = 10.0;
  std::vector<double> target;
  double target_weight = 0.0;
  std::map<std::string, double> workspace;  ///< x_min, x_max, y_min, ...
};

/// The node's private parameters (config/fesd_trajopt.yaml).
struct NodeConfig {
  std::string frame_id = "world";
  bool planar = true;
  double horizon = 5.0;
  int num_intervals = 40;
  double control_weight = 1e-4;
  int num_elements = 3;
  int num_stages = 2;
  bool fesd = true;
  double complementarity_tolerance = 1e-9;
  double wall_time_budget = 120.0;
  int verification_stages = 3;
  int verification_elements = 6;
  /// ~target_accuracy: a request's accuracy ladder when it names none (0: unverified answers)
  double target_accuracy = 1e-2;
  double playback_rate = 1.0;   ///< ~playback at this many times real time; 0: off
  bool lazy_pairs = true;       ///< ~contact_pairs: lazy (default) or all_in_reach
  double contact_margin = 0.1;  ///< ~contact_margin: lazy pairs' margin, relative to the radii
  /// ~robot_all_pairs_up_to: with lazy contact_pairs, a robot scene with at most this many pairs
  /// in reach still models them all (lazy rounds can end in other local optima, and few pairs
  /// are cheap); more (a Panda's 118) are lazy.
  int robot_all_pairs_up_to = 32;
  /// ~linear_solver: the KKT solve behind Ipopt, "ldlt" (ours; solves run in parallel) or
  /// "mumps" (Debian's Ipopt's own; one solve at a time in the process).
  std::string linear_solver = "ldlt";
  /// ~mpcc_method: "homotopy" (relaxed NLPs to the tolerance, then the active set polished) or
  /// "active_set" (relaxed NLPs only until a branch NLP solves, then LPECs and branch NLPs).
  fesd::MpccMethod mpcc_method = fesd::MpccMethod::kHomotopy;
  /// ~solver_threads: requests (services and action goals) solved at once; 0: one per core.
  int solver_threads = 0;
  fesd::TaskLimits limits;
  /// ~limits/max_sensitivity_entries: the numbers a ~simulate answer's sensitivities may hold.
  double max_sensitivity_entries = 4e6;
  std::map<std::string, BodyConfig> bodies;
  std::string scene_urdf;  ///< ~scene_urdf: the default scene
  /// ~interactive_targets: targets dragged in rviz replan the last request (~targets)
  bool interactive_targets = true;
};

/// Reads the private parameters; throws std::runtime_error naming a malformed one.
NodeConfig loadNodeConfig(const ros::NodeHandle& private_node);

}  // namespace fesd_ros
