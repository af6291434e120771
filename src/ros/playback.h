#pragma once

#include <mutex>
#include <string>

#include <fesd_trajopt/Solution.h>
#include <ros/callback_queue.h>
#include <ros/node_handle.h>
#include <ros/spinner.h>
#include <ros/wall_timer.h>

namespace fesd_ros {

/// Plays the last solution back in rviz: the bodies on ~playback (visualization_msgs/
/// MarkerArray, namespace "playback") at solution time rate * (wall time since the solve),
/// between element boundaries linearly, then again after a pause of a second. Its timer has its
/// own callback queue and thread, so frames keep coming while the node's spinner threads solve.
/// A robot solution's joints go out as sensor_msgs/JointState on ~joint_states at each frame
/// (positions linear between the element boundaries), for robot_state_publisher and rviz.
class Playback {
 public:
  /// rate <= 0: no playback.
  Playback(const ros::NodeHandle& private_node, double rate, double frames_per_second);
  ~Playback();
  Playback(const Playback&) = delete;
  Playback& operator=(const Playback&) = delete;
  /// Starts playing `solution` from its beginning (planar: bodies as discs).
  void play(const fesd_trajopt::Solution& solution, bool planar);

 private:
  void showFrame();
  void publishJointState(double t);

  double rate_;
  ros::CallbackQueue callbacks_;
  ros::AsyncSpinner spinner_;
  ros::Publisher publisher_, joint_state_publisher_;
  ros::WallTimer timer_;
  std::mutex mutex_;
  fesd_trajopt::Solution solution_;
  bool planar_ = true;
  ros::WallTime start_;
};

}  // namespace fesd_ros
