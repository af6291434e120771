#include "playback.h"

#include <algorithm>
#include <cmath>

#include <sensor_msgs/JointState.h>
#include <visualization_msgs/MarkerArray.h>

#include "solution_message.h"

namespace fesd_ros {
namespace {

constexpr double kPauseSeconds = 1.0;  // between the end of one pass and the next

/// A body's position and yaw at time t, linear between the element boundaries.
std::pair<geometry_msgs::Point, double> poseAt(const fesd_trajopt::Solution& solution,
                                               const fesd_trajopt::BodyTrajectory& body, double t) {
  const std::vector<double>& times = solution.times;
  const size_t k = std::upper_bound(times.begin(), times.end(), t) - times.begin();
  if (k == 0) return {body.positions.front(), yawAt(body, 0)};
  if (k >= times.size()) return {body.positions.back(), yawAt(body, times.size() - 1)};
  const double span = times[k] - times[k - 1];
  const double w = span > 0.0 ? (t - times[k - 1]) / span : 1.0;
  const geometry_msgs::Point &a = body.positions[k - 1], &b = body.positions[k];
  geometry_msgs::Point p;
  p.x = a.x + w * (b.x - a.x);
  p.y = a.y + w * (b.y - a.y);
  p.z = a.z + w * (b.z - a.z);
  return {p, yawAt(body, k - 1) + w * (yawAt(body, k) - yawAt(body, k - 1))};
}

}  // namespace

Playback::Playback(const ros::NodeHandle& private_node, double rate, double frames_per_second)
    : rate_(rate), spinner_(1, &callbacks_) {
  if (rate_ <= 0.0) return;
  ros::NodeHandle node(private_node);
  node.setCallbackQueue(&callbacks_);
  publisher_ = node.advertise<visualization_msgs::MarkerArray>("playback", 1);
  joint_state_publisher_ = node.advertise<sensor_msgs::JointState>("joint_states", 1);
  timer_ = node.createWallTimer(ros::WallDuration(1.0 / frames_per_second),
                                [this](const ros::WallTimerEvent&) { showFrame(); });
  spinner_.start();
}

Playback::~Playback() {
  spinner_.stop();  // no frame may run while the members go
  timer_.stop();
}

void Playback::play(const fesd_trajopt::Solution& solution, bool planar) {
  if (rate_ <= 0.0) return;
  std::lock_guard<std::mutex> lock(mutex_);
  solution_ = solution;
  planar_ = planar;
  start_ = ros::WallTime::now();
}

void Playback::showFrame() {
  std::lock_guard<std::mutex> lock(mutex_);
  if (solution_.times.empty()) return;
  const double duration = solution_.times.back() - solution_.times.front();
  const double period = duration + kPauseSeconds * rate_;
  const double played = (ros::WallTime::now() - start_).toSec() * rate_;
  const double t = solution_.times.front() + std::min(std::fmod(played, period), duration);
  publishJointState(t);
  if (publisher_.getNumSubscribers() == 0) return;
  visualization_msgs::MarkerArray frame;
  int id = 0;  // the same ids in every frame: each replaces its own marker
  for (size_t b = 0; b < solution_.bodies.size(); ++b) {
    const fesd_trajopt::BodyTrajectory& body = solution_.bodies[b];
    if (body.positions.size() != solution_.times.size()) continue;
    const auto [position, yaw] = poseAt(solution_, body, t);
    for (const auto& [centre, radius] : bodySpheres(body, position, yaw)) {
      visualization_msgs::Marker m;
      m.header.frame_id = solution_.header.frame_id;
      m.header.stamp = ros::Time::now();
      m.ns = "playback";
      m.id = id++;
      m.type = planar_ ? visualization_msgs::Marker::CYLINDER : visualization_msgs::Marker::SPHERE;
      m.action = visualization_msgs::Marker::ADD;
      m.pose.position = centre;
      m.pose.orientation.w = 1.0;
      m.scale.x = m.scale.y = 2.0 * radius;
      m.scale.z = planar_ ? 0.15 : 2.0 * radius;
      m.color = bodyColor(body.actuated, 1.0);
      frame.markers.push_back(m);
    }
  }
  publisher_.publish(frame);
}

void Playback::publishJointState(double t) {
  const trajectory_msgs::JointTrajectory& motion = solution_.joint_trajectory;
  if (motion.joint_names.empty() || motion.points.size() != solution_.times.size() ||
      joint_state_publisher_.getNumSubscribers() == 0) {
    return;
  }
  const std::vector<double>& times = solution_.times;
  const size_t k = std::upper_bound(times.begin(), times.end(), t) - times.begin();
  const size_t before = k == 0 ? 0 : std::min(k - 1, times.size() - 1);
  const size_t after = std::min(k, times.size() - 1);
  const double span = times[after] - times[before];
  const double w = span > 0.0 ? (t - times[before]) / span : 0.0;
  sensor_msgs::JointState state;
  state.header.stamp = ros::Time::now();
  state.name = motion.joint_names;
  for (size_t j = 0; j < motion.joint_names.size(); ++j) {
    const double a = motion.points[before].positions[j], b = motion.points[after].positions[j];
    state.position.push_back(a + w * (b - a));
  }
  joint_state_publisher_.publish(state);
}

}  // namespace fesd_ros
