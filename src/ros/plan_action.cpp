#include "plan_action.h"

#include <actionlib_msgs/GoalStatus.h>
#include <fesd_trajopt/Solution.h>

#include "fesd_trajopt/solver/stopwatch.h"
#include "solution_message.h"

namespace fesd_ros {
namespace {

fesd_trajopt::PlanTrajectoryResult unsolved(uint8_t status, const std::string& message) {
  fesd_trajopt::PlanTrajectoryResult result;
  setUnsolved(result, status, message);
  return result;
}

/// `node` with its callbacks on `queue`.
ros::NodeHandle onQueue(ros::NodeHandle node, ros::CallbackQueue* queue) {
  node.setCallbackQueue(queue);
  return node;
}

}  // namespace

PlanActionServer::PlanActionServer(const ros::NodeHandle& private_node, int workers, Plan plan)
    : plan_(std::move(plan)),
      node_(onQueue(private_node, &callbacks_)),
      server_(
          node_, "plan", [this](GoalHandle goal) { receive(goal); },
          [this](GoalHandle goal) { cancel(goal); }, false),
      spinner_(1, &callbacks_) {
  for (int w = 0; w < workers; ++w) workers_.emplace_back([this] { work(); });
}

PlanActionServer::~PlanActionServer() {
  spinner_.stop();
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    for (auto& [id, cancel] : running_) *cancel = true;
    for (GoalHandle& goal : queue_) {
      goal.setAborted(unsolved(fesd_trajopt::Solution::CANCELLED, "the node is shutting down"));
    }
    queue_.clear();
  }
  wake_.notify_all();
  for (std::thread& worker : workers_) worker.join();
}

void PlanActionServer::start() {
  server_.start();
  spinner_.start();
}

void PlanActionServer::receive(GoalHandle goal) {
  std::lock_guard<std::mutex> lock(mutex_);
  queue_.push_back(goal);
  ROS_INFO_STREAM("fesd_trajopt: plan goal " << goal.getGoalID().id << " queued (" << queue_.size()
                                             << " waiting)");
  wake_.notify_one();
}

void PlanActionServer::cancel(GoalHandle goal) {
  std::lock_guard<std::mutex> lock(mutex_);
  const auto running = running_.find(goal.getGoalID().id);
  if (running != running_.end()) {
    *running->second = true;  // its worker ends it with the best iterate
    return;
  }
  for (auto queued = queue_.begin(); queued != queue_.end(); ++queued) {
    if (*queued == goal) {
      queued->setCanceled(
          unsolved(fesd_trajopt::Solution::CANCELLED, "cancelled before it started"));
      queue_.erase(queued);
      return;
    }
  }
  // Not queued yet (a cancel can overtake the goal's own callback): the worker sees the goal
  // RECALLING when it comes to it.
}

void PlanActionServer::work() {
  while (true) {
    GoalHandle goal;
    auto cancel = std::make_shared<std::atomic<bool>>(false);
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      goal = queue_.front();
      queue_.pop_front();
      if (goal.getGoalStatus().status == actionlib_msgs::GoalStatus::RECALLING) {
        goal.setCanceled(
            unsolved(fesd_trajopt::Solution::CANCELLED, "cancelled before it started"));
        continue;
      }
      running_[goal.getGoalID().id] = cancel;
    }
    try {
      run(goal, *cancel);
    } catch (...) {
      // plan_ answers errors itself; this is actionlib or memory failing: end the goal anyway.
      ROS_ERROR_STREAM("fesd_trajopt: plan goal " << goal.getGoalID().id << " failed unexpectedly");
      goal.setAborted(unsolved(fesd_trajopt::Solution::SOLVER_ERROR, "internal error"));
    }
    std::lock_guard<std::mutex> lock(mutex_);
    running_.erase(goal.getGoalID().id);
  }
}

void PlanActionServer::run(GoalHandle& goal, const std::atomic<bool>& cancel) {
  goal.setAccepted("solving");
  const fesd::Stopwatch elapsed;
  fesd_trajopt::PlanTrajectoryFeedback feedback;
  fesd::SolveMonitor monitor;
  monitor.cancel = &cancel;
  monitor.on_step = [&](const fesd::HomotopyStep& step) {
    ++feedback.homotopy_step;
    feedback.sigma = step.sigma;
    feedback.phase = step.sigma > 0.0 ? "relaxed NLP" : "branch NLP";
    feedback.ipopt_iterations += step.iterations;
    feedback.complementarity_residual = step.complementarity_residual;
    feedback.objective = step.objective;
    feedback.elapsed = elapsed.wallSeconds();
    goal.publishFeedback(feedback);
  };
  fesd_trajopt::PlanTrajectoryResult result;
  plan_(goal.getGoal()->request, monitor, result);
  if (result.status == fesd_trajopt::Solution::CANCELLED) {
    goal.setCanceled(result, result.message);
  } else if (result.status == fesd_trajopt::Solution::SUCCESS) {
    goal.setSucceeded(result, result.message);
  } else {
    goal.setAborted(result, result.message);
  }
}

}  // namespace fesd_ros
