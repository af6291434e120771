#include "interactive_targets.h"

#include <algorithm>
#include <cmath>

#include <visualization_msgs/InteractiveMarkerFeedback.h>

namespace fesd_ros {
namespace {

using Feedback = visualization_msgs::InteractiveMarkerFeedback;

geometry_msgs::Quaternion yawQuaternion(double yaw) {
  geometry_msgs::Quaternion q;
  q.z = std::sin(0.5 * yaw);
  q.w = std::cos(0.5 * yaw);
  return q;
}

/// A control acting in the x-y plane: its axis (the control frame's x) turned onto z.
visualization_msgs::InteractiveMarkerControl planeControl(const std::string& name, uint8_t mode) {
  visualization_msgs::InteractiveMarkerControl control;
  control.name = name;
  control.orientation.w = control.orientation.y = std::sqrt(0.5);
  control.interaction_mode = mode;
  control.always_visible = true;
  return control;
}

const char* actionName(InteractiveTargets::Action action) {
  return action == InteractiveTargets::Action::kPlan ? "plan" : "execute with feedback";
}

}  // namespace

InteractiveTargets::InteractiveTargets(const ros::NodeHandle& private_node,
                                       const std::string& frame_id, Solve solve)
    : frame_id_(frame_id),
      solve_(std::move(solve)),
      // Its own callback thread: dragging is taken while every spinner thread serves a solve.
      server_(private_node.resolveName("targets"), "", true),
      worker_(
          [this](Job& job) {
            fesd::SolveMonitor monitor;
            monitor.cancel = &stopping_;
            solve_(job.request, job.action, monitor);
          },
          kSolveSpacing) {
  menu_.insert("Plan", [this](const visualization_msgs::InteractiveMarkerFeedbackConstPtr&) {
    solveDragged(Action::kPlan);
  });
  menu_.insert("Execute with feedback",
               [this](const visualization_msgs::InteractiveMarkerFeedbackConstPtr&) {
                 solveDragged(Action::kExecuteWithFeedback);
               });
  menu_.insert("Reset targets",
               [this](const visualization_msgs::InteractiveMarkerFeedbackConstPtr&) { reset(); });
}

InteractiveTargets::~InteractiveTargets() {
  stopping_ = true;
}

void InteractiveTargets::show(const fesd_trajopt::PlanRequest& request,
                              const fesd::SceneTask& task) {
  std::vector<visualization_msgs::InteractiveMarker> markers;
  {
    std::lock_guard<std::mutex> lock(mutex_);
    request_ = request;
    targets_.clear();
    for (size_t b = 0; b < task.bodies.size(); ++b) {
      const fesd::BodyTask& body = task.bodies[b];
      if (!body.hasTarget()) continue;
      Target target;
      target.name = task.scene.bodies()[b].name;
      target.radius = task.scene.bodies()[b].radius;
      target.region = targetRegion(task, static_cast<int>(b));
      target.weight = body.target_weight;
      target.position = target.requested_position = body.target;
      target.has_yaw = task.scene.bodies()[b].turns && body.hasYawTarget();
      target.yaw_weight = body.target_yaw_weight;
      target.yaw = target.requested_yaw = body.target_yaw;
      targets_.push_back(target);
      markers.push_back(marker(target));
    }
  }
  server_.clear();
  for (const visualization_msgs::InteractiveMarker& m : markers) {
    server_.insert(
        m, [this](const visualization_msgs::InteractiveMarkerFeedbackConstPtr& f) { receive(f); });
    menu_.apply(server_, m.name);
  }
  server_.applyChanges();
  ROS_INFO_STREAM("fesd_trajopt: " << markers.size() << " interactive target(s) on ~targets");
}

visualization_msgs::InteractiveMarker InteractiveTargets::marker(const Target& target) const {
  visualization_msgs::InteractiveMarker marker;
  marker.header.frame_id = frame_id_;
  marker.name = target.name;
  marker.description = target.name + " target";
  marker.scale = static_cast<float>(3.0 * target.radius);
  marker.pose.position.x = target.position(0);
  marker.pose.position.y = target.position(1);
  if (target.position.size() == 3) marker.pose.position.z = target.position(2);
  marker.pose.orientation = yawQuaternion(target.yaw);
  marker.controls.push_back(
      planeControl("move", visualization_msgs::InteractiveMarkerControl::MOVE_PLANE));
  if (target.has_yaw) {
    marker.controls.push_back(
        planeControl("turn", visualization_msgs::InteractiveMarkerControl::ROTATE_AXIS));
  }
  return marker;
}

InteractiveTargets::Target* InteractiveTargets::find(const std::string& name) {
  for (Target& target : targets_) {
    if (target.name == name) return &target;
  }
  return nullptr;
}

void InteractiveTargets::placeMarker(const Target& target) {
  geometry_msgs::Pose pose;
  pose.position.x = target.position(0);
  pose.position.y = target.position(1);
  if (target.position.size() == 3) pose.position.z = target.position(2);
  pose.orientation = yawQuaternion(target.yaw);
  server_.setPose(target.name, pose);
}

void InteractiveTargets::receive(const visualization_msgs::InteractiveMarkerFeedbackConstPtr& f) {
  if (f->event_type != Feedback::POSE_UPDATE && f->event_type != Feedback::MOUSE_UP) return;
  std::unique_lock<std::mutex> lock(mutex_);
  Target* target = find(f->marker_name);
  if (target == nullptr) {
    ROS_WARN_STREAM_THROTTLE(1.0, "fesd_trajopt: ~targets: no target named '"
                                      << f->marker_name << "'; feedback ignored");
    return;
  }
  std::string refused;
  if (!f->header.frame_id.empty() && f->header.frame_id != frame_id_) {
    refused = "a pose in frame '" + f->header.frame_id + "', not ~frame_id '" + frame_id_ + "'";
  }
  const geometry_msgs::Pose& pose = f->pose;
  const TargetPlacement placement =
      placeTarget(target->region, {pose.position.x, pose.position.y, pose.position.z},
                  {pose.orientation.x, pose.orientation.y, pose.orientation.z, pose.orientation.w},
                  target->position.size() == 3 ? target->position(2) : 0.0, target->yaw);
  if (refused.empty()) refused = placement.refused;
  if (refused.empty()) {
    target->position = placement.position;
    if (target->has_yaw) target->yaw = placement.yaw;
  } else {
    ROS_WARN_STREAM_THROTTLE(
        1.0, "fesd_trajopt: ~targets: " << target->name << ": " << refused << "; the target stays");
  }
  // Also after a refused pose: the server took it already, the marker goes back.
  placeMarker(*target);
  server_.applyChanges();
  lock.unlock();
  if (f->event_type == Feedback::MOUSE_UP && refused.empty()) solveDragged(Action::kPlan);
}

void InteractiveTargets::solveDragged(Action action) {
  Job job{{}, action};
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job.request = request_;
    for (const Target& target : targets_) {
      auto spec =
          std::find_if(job.request.bodies.begin(), job.request.bodies.end(),
                       [&](const fesd_trajopt::BodySpec& b) { return b.name == target.name; });
      if (spec == job.request.bodies.end()) {
        job.request.bodies.emplace_back();
        spec = job.request.bodies.end() - 1;
        spec->name = target.name;
      }
      spec->target.x = target.position(0);
      spec->target.y = target.position(1);
      spec->target.z = target.position.size() == 3 ? target.position(2) : 0.0;
      spec->target_weight = target.weight;
      if (target.has_yaw) {
        spec->target_yaw = target.yaw;
        spec->target_yaw_weight = target.yaw_weight;
      }
    }
  }
  job.request.warm_start = true;  // from the last plan
  const bool superseded = worker_.post(std::move(job));
  ROS_INFO_STREAM("fesd_trajopt: ~targets: " << actionName(action) << " queued"
                                             << (superseded ? " (replacing the one waiting)" : ""));
}

void InteractiveTargets::reset() {
  std::lock_guard<std::mutex> lock(mutex_);
  for (Target& target : targets_) {
    target.position = target.requested_position;
    target.yaw = target.requested_yaw;
    placeMarker(target);
  }
  server_.applyChanges();
}

}  // namespace fesd_ros
