#pragma once

#include <atomic>
#include <condition_variable>
#include <deque>
#include <functional>
#include <map>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include <actionlib/server/action_server.h>
#include <fesd_trajopt/PlanTrajectoryAction.h>
#include <ros/callback_queue.h>
#include <ros/node_handle.h>
#include <ros/spinner.h>

#include "fesd_trajopt/solver/mpcc_solver.h"

namespace fesd_ros {

/// The ~plan action. Goals queue and run on `workers` threads, each goal with its own solve, so a
/// new goal never touches one in progress. Feedback follows every relaxed NLP; cancelling a
/// running goal stops its solve at the next Ipopt iteration (a verification re-simulation in
/// progress finishes first) and ends it PREEMPTED with the best iterate; cancelling a queued
/// goal ends it RECALLED without a solve. The action's callbacks have their own queue and
/// thread, so cancels are taken even while every spinner thread of the node serves a long
/// service call.
class PlanActionServer {
 public:
  /// Solves a request, watched by the monitor, into the result (status, message, solution).
  using Plan = std::function<void(const fesd_trajopt::PlanRequest&, const fesd::SolveMonitor&,
                                  fesd_trajopt::PlanTrajectoryResult&)>;

  PlanActionServer(const ros::NodeHandle& private_node, int workers, Plan plan);
  /// Cancels the running goals and aborts the queued ones.
  ~PlanActionServer();
  PlanActionServer(const PlanActionServer&) = delete;
  PlanActionServer& operator=(const PlanActionServer&) = delete;

  /// Starts taking goals (once everything `plan` uses is ready).
  void start();

 private:
  using Server = actionlib::ActionServer<fesd_trajopt::PlanTrajectoryAction>;
  using GoalHandle = Server::GoalHandle;

  void receive(GoalHandle goal);
  void cancel(GoalHandle goal);
  void work();
  void run(GoalHandle& goal, const std::atomic<bool>& cancel);

  Plan plan_;
  ros::CallbackQueue callbacks_;
  ros::NodeHandle node_;  ///< the private node on callbacks_
  Server server_;
  ros::AsyncSpinner spinner_;
  std::mutex mutex_;
  std::condition_variable wake_;
  std::deque<GoalHandle> queue_;
  /// The goals being solved, by goal id, each with the flag that cancels it.
  std::map<std::string, std::shared_ptr<std::atomic<bool>>> running_;
  bool stopping_ = false;
  std::vector<std::thread> workers_;
};

}  // namespace fesd_ros
