#include "plan_action.h"

#include <fesd_trajopt/Solution.h>

#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd_ros {

PlanActionServer::PlanActionServer(ros::NodeHandle private_node, Plan plan)
    : plan_(std::move(plan)),
      server_(
          private_node, "plan", [this](GoalHandle goal) { receive(goal); },
          [this](GoalHandle goal) { cancel(goal); }, false) {
  worker_ = std::thread([this] { work(); });
}

PlanActionServer::~PlanActionServer() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    cancel_running_ = true;
  }
  wake_.notify_all();
  worker_.join();
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
  if (goal.getGoalID().id == running_) {
    cancel_running_ = true;  // the worker ends it with the best iterate
    return;
  }
  for (auto queued = queue_.begin(); queued != queue_.end(); ++queued) {
    if (*queued == goal) {
      fesd_trajopt::PlanTrajectoryResult result;
      result.status = result.solution.status = fesd_trajopt::Solution::CANCELLED;
      result.message = result.solution.message = "cancelled before it started";
      queued->setCanceled(result, result.message);
      queue_.erase(queued);
      return;
    }
  }
}

void PlanActionServer::work() {
  while (true) {
    GoalHandle goal;
    {
      std::unique_lock<std::mutex> lock(mutex_);
      wake_.wait(lock, [this] { return stopping_ || !queue_.empty(); });
      if (stopping_) return;
      goal = queue_.front();
      queue_.pop_front();
      running_ = goal.getGoalID().id;
      cancel_running_ = false;
    }
    run(goal);
    std::lock_guard<std::mutex> lock(mutex_);
    running_.clear();
  }
}

void PlanActionServer::run(GoalHandle& goal) {
  goal.setAccepted("solving");
  const fesd::Stopwatch elapsed;
  fesd_trajopt::PlanTrajectoryFeedback feedback;
  fesd::SolveMonitor monitor;
  monitor.cancel = &cancel_running_;
  monitor.on_step = [&](const fesd::HomotopyStep& step) {
    ++feedback.homotopy_step;
    feedback.sigma = step.sigma;
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
