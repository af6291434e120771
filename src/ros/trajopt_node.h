#pragma once

#include <map>
#include <memory>
#include <mutex>
#include <string>

#include <fesd_trajopt/PlanTrajectoryAction.h>
#include <fesd_trajopt/Simulate.h>
#include <fesd_trajopt/SolveTrajectory.h>
#include <ros/ros.h>
#include <tf2_ros/static_transform_broadcaster.h>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "interactive_targets.h"
#include "node_config.h"
#include "plan_action.h"
#include "playback.h"
#include "scene_request.h"
#include "solve_slots.h"

namespace fesd_ros {

/// The fesd_trajopt node: ~solve_trajectory and ~simulate services and the ~plan action (the
/// same request as ~solve_trajectory, with progress and cancel); latched ~markers
/// (visualization_msgs/MarkerArray), ~solution (fesd_trajopt/Solution) and ~paths/<body>
/// (nav_msgs/Path) topics; ~playback, the last solution's motion; a static transform that makes
/// ~frame_id exist for rviz; with ~interactive_targets, targets dragged in rviz (~targets) that
/// replan the last request (the default scene's before any). Requests are served concurrently, up
/// to ~solver_threads at once, each with its own solver (with ~linear_solver mumps their Ipopt
/// solves take turns: MUMPS is not thread-safe). The last solution of its NLP, of a disc or a robot
/// scene, is kept for warm starts.
class TrajoptNode {
 public:
  TrajoptNode(ros::NodeHandle node, ros::NodeHandle private_node);
  /// Threads the node's services should be spun with: one per request solved at once.
  int solverThreads() const { return config_.solver_threads; }

 private:
  bool solveTrajectory(fesd_trajopt::SolveTrajectory::Request& request,
                       fesd_trajopt::SolveTrajectory::Response& response);
  bool simulate(fesd_trajopt::Simulate::Request& request,
                fesd_trajopt::Simulate::Response& response);
  /// A plan request (service, action goal or dragged targets) answered; `monitor` watches the
  /// solve. `solved`, if given, receives the outcome when it solved its NLP.
  void plan(const fesd_trajopt::PlanRequest& request, const fesd::SolveMonitor* monitor,
            fesd_trajopt::PlanTrajectoryResult& answer,
            std::shared_ptr<const fesd::SceneOutcome>* solved = nullptr);
  void handlePlan(const fesd_trajopt::PlanRequest& request, const fesd::SolveMonitor* monitor,
                  fesd_trajopt::PlanTrajectoryResult& answer,
                  std::shared_ptr<const fesd::SceneOutcome>* solved);
  /// The scene task of a plan request (its horizon and intervals applied).
  TaskBuild planTask(const fesd_trajopt::PlanRequest& request) const;
  /// The solver options of a plan request; "" or why it is refused.
  std::string planOptions(const fesd_trajopt::PlanRequest& request, bool robot,
                          const fesd::SolveMonitor* monitor,
                          fesd::SceneSolveOptions& options) const;
  /// The interactive targets start at a request the node served (the caller leaves out refused
  /// ones).
  void showTargets(const fesd_trajopt::PlanRequest& request);
  /// Dragged targets' request: planned, and with kExecuteWithFeedback the plan then executed.
  void solveTargets(const fesd_trajopt::PlanRequest& request, InteractiveTargets::Action action,
                    const fesd::SolveMonitor& monitor);
  /// A plan executed with feedback against the simulated plant (executeWithFeedback); publishes
  /// the executed motion.
  void executeWithFeedback(const fesd_trajopt::PlanRequest& request, const fesd::SceneOutcome& plan,
                           const fesd::SolveMonitor& monitor);
  /// The answer, its markers (with the push plan's legs and transits) and, with a robot, its
  /// root frame.
  void publish(const fesd::SceneTask& task, const fesd_trajopt::Solution& solution,
               const std::vector<fesd::PushLeg>& legs = {},
               const std::vector<fesd::Transit>& transits = {});
  void publishPaths(const fesd_trajopt::Solution& solution);
  void handleSimulate(const fesd_trajopt::Simulate::Request& request,
                      fesd_trajopt::Simulate::Response& response);

  ros::NodeHandle node_, private_node_;
  NodeConfig config_;
  SolveSlots slots_;
  ros::ServiceServer solve_service_, simulate_service_;
  ros::Publisher marker_publisher_, solution_publisher_;
  std::map<std::string, ros::Publisher> path_publishers_;  ///< by body name, latched
  tf2_ros::StaticTransformBroadcaster frame_broadcaster_;
  std::mutex publish_mutex_;
  Playback playback_;
  std::mutex last_solution_mutex_;
  std::shared_ptr<const fesd::SceneOutcome> last_solution_;  ///< for warm starts
  PlanActionServer plan_server_;                 ///< its worker thread uses everything above
  std::unique_ptr<InteractiveTargets> targets_;  ///< last: its worker uses everything above
};

}  // namespace fesd_ros
