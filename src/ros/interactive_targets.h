#pragma once

#include <atomic>
#include <chrono>
#include <functional>
#include <mutex>
#include <string>
#include <vector>

#include <fesd_trajopt/PlanRequest.h>
#include <interactive_markers/interactive_marker_server.h>
#include <interactive_markers/menu_handler.h>
#include <ros/node_handle.h>
#include <Eigen/Dense>

#include "fesd_trajopt/scene/scene_task.h"
#include "fesd_trajopt/solver/mpcc_solver.h"
#include "latest_wins_worker.h"
#include "target_region.h"

namespace fesd_ros {

/// Targets dragged in rviz: an interactive marker server under ~targets with one marker per body
/// of the last request that has a target (named as the body), moving in the scene's plane (a
/// spatial scene's: at the target's height), with a ring for a turning body's target yaw, and a
/// menu (Plan, Execute with feedback, Reset targets). A release (MOUSE_UP) or Plan solves the
/// last request with the dragged targets on its own worker thread: at most one solve runs and
/// one waits, a newer release replacing the waiting one, and solves start kSolveSpacing apart
/// (releases in between coalesce); dragging (POSE_UPDATE) only moves the marker. Poses that are not
/// finite, outside the body's workspace bounds or beyond kTargetReachInSceneSizes are refused (a
/// warning; the marker goes back).
class InteractiveTargets {
 public:
  enum class Action { kPlan, kExecuteWithFeedback };
  /// The least time between the starts of two solves: a burst of releases (a flood of feedback,
  /// or clicks) costs two solves, a person dragging waits at most this for the second.
  static constexpr std::chrono::milliseconds kSolveSpacing{1000};
  /// Solves a request as the node's services do (slots, budget, publishing), watched by `monitor`.
  using Solve = std::function<void(const fesd_trajopt::PlanRequest&, Action,
                                   const fesd::SolveMonitor& monitor)>;

  InteractiveTargets(const ros::NodeHandle& private_node, const std::string& frame_id, Solve solve);
  /// Stops the running solve at its next Ipopt iteration and drops the waiting one.
  ~InteractiveTargets();
  InteractiveTargets(const InteractiveTargets&) = delete;
  InteractiveTargets& operator=(const InteractiveTargets&) = delete;

  /// Markers for a request (its task, as built for its solve): they start at its targets.
  void show(const fesd_trajopt::PlanRequest& request, const fesd::SceneTask& task);

 private:
  /// A body's target as dragged, and as the request had it (for Reset).
  struct Target {
    std::string name;
    double radius = 1.0;
    TargetRegion region;
    double weight = 0.0;
    Eigen::VectorXd position, requested_position;
    bool has_yaw = false;  ///< a turning body with a yaw target: it gets a ring
    double yaw_weight = 0.0, yaw = 0.0, requested_yaw = 0.0;
  };
  struct Job {
    fesd_trajopt::PlanRequest request;
    Action action;
  };

  void receive(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& feedback);
  /// The last request with the dragged targets, posted for a solve.
  void solveDragged(Action action);
  void reset();
  /// Puts the server's marker of a target where the target is (the caller applies the changes).
  void placeMarker(const Target& target);
  visualization_msgs::InteractiveMarker marker(const Target& target) const;
  Target* find(const std::string& name);

  std::string frame_id_;
  Solve solve_;
  std::mutex mutex_;  ///< request_ and targets_; taken inside the server's lock, never around it
  fesd_trajopt::PlanRequest request_;
  std::vector<Target> targets_;
  interactive_markers::InteractiveMarkerServer server_;
  interactive_markers::MenuHandler menu_;
  std::atomic<bool> stopping_{false};
  LatestWinsWorker<Job> worker_;  ///< last: its thread uses everything above
};

}  // namespace fesd_ros
