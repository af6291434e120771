#include "robot_solution.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "solution_message.h"

namespace fesd_ros {
namespace {

/// The velocity of the actual motion (command plus the contacts' projection) at each element
/// boundary: the DCS velocity at the boundary state with the multipliers of the element's stage
/// there (Radau: its last stage is its end; the start takes the first element's first stage).
std::vector<Eigen::VectorXd> boundaryVelocities(const fesd::SceneTask& task,
                                                const fesd::SceneOutcome& outcome) {
  const fesd::Trajectory& trajectory = outcome.trajectory;
  std::vector<Eigen::VectorXd> velocities;
  if (trajectory.elements.size() + 1 != trajectory.states.size()) return velocities;
  const auto model = task.scene.model(outcome.modelled);
  const int nx = model->stateSize(), nu = model->controlSize(), nc = model->constraintSize();
  Eigen::VectorXd z(nx + nu + nc), v(nx);
  for (size_t i = 0; i < trajectory.states.size(); ++i) {
    const fesd::ElementValues& element = trajectory.elements[i == 0 ? 0 : i - 1];
    const Eigen::MatrixXd& multipliers = element.stage_multipliers;
    z.head(nx) = trajectory.states[i];
    z.segment(nx, nu) = trajectory.controls[element.interval];
    if (nc > 0) {
      z.tail(nc) = multipliers.col(i == 0 ? 0 : multipliers.cols() - 1);
    }
    model->velocity()->evaluate(z.data(), v.data());
    velocities.push_back(v);
  }
  return velocities;
}

/// sceneMarkers draws paths and labels for the node's default scene (metres across); a robot
/// scene is a tenth of that: thinner paths, smaller labels in a column right of the robot and
/// what it pushes (its spheres are drawn after sceneMarkers placed the labels).
void fitToRobotScale(visualization_msgs::MarkerArray& markers) {
  constexpr double kPathWidth = 0.008, kLabelHeight = 0.03;
  double right = -INFINITY, top = -INFINITY;
  for (visualization_msgs::Marker& m : markers.markers) {
    if (m.ns == "paths") m.scale.x = kPathWidth;
    if (m.ns == "switch_labels") m.scale.z = kLabelHeight;
    if (m.type != visualization_msgs::Marker::SPHERE &&
        m.type != visualization_msgs::Marker::CYLINDER) {
      continue;
    }
    right = std::max(right, m.pose.position.x + 0.5 * m.scale.x);
    top = std::max(top, m.pose.position.y + 0.5 * m.scale.y);
  }
  stackSwitchLabels(right + kLabelHeight, top, 1.2 * kLabelHeight, markers);
}
}  // namespace

void addJointTrajectories(const fesd::SceneTask& task, const fesd::SceneOutcome& outcome,
                          fesd_trajopt::Solution& solution) {
  const fesd::Scene& scene = task.scene;
  const fesd::Trajectory& trajectory = outcome.trajectory;
  const int joints = scene.numJoints();
  trajectory_msgs::JointTrajectory& motion = solution.joint_trajectory;
  trajectory_msgs::JointTrajectory& commands = solution.joint_commands;
  for (const fesd::KinematicJoint& joint : scene.robot().joints) {
    motion.joint_names.push_back(joint.name);
    commands.joint_names.push_back(joint.name);
  }
  const std::vector<Eigen::VectorXd> velocities = boundaryVelocities(task, outcome);
  for (size_t i = 0; i < trajectory.states.size(); ++i) {
    trajectory_msgs::JointTrajectoryPoint point;
    const Eigen::VectorXd q = trajectory.states[i].head(joints);
    point.positions.assign(q.data(), q.data() + joints);
    if (i < velocities.size()) {
      point.velocities.assign(velocities[i].data(), velocities[i].data() + joints);
    }
    point.time_from_start = ros::Duration(trajectory.times[i]);
    motion.points.push_back(point);
  }
  for (size_t k = 0; k < trajectory.controls.size(); ++k) {
    trajectory_msgs::JointTrajectoryPoint point;
    const Eigen::VectorXd u = trajectory.controls[k].head(joints);
    point.velocities.assign(u.data(), u.data() + joints);
    if (k < trajectory.interval_times.size()) {
      point.time_from_start = ros::Duration(trajectory.interval_times[k]);
    }
    commands.points.push_back(point);
  }
}

void addRobotMarkers(const fesd::SceneTask& task, const fesd_trajopt::Solution& solution,
                     const std::string& frame_id, visualization_msgs::MarkerArray& markers) {
  const fesd::KinematicModel& robot = task.scene.robot();
  const auto& points = solution.joint_trajectory.points;
  if (points.empty()) return fitToRobotScale(markers);
  // After sceneMarkers' ids, so that no marker replaces another.
  int id = static_cast<int>(markers.markers.size());
  fesd::KinematicData data;
  auto sphere = [&](const std::string& ns, const geometry_msgs::Point& centre, double radius,
                    const std_msgs::ColorRGBA& color) {
    visualization_msgs::Marker m;
    m.header.frame_id = frame_id;
    m.header.stamp = solution.header.stamp;
    m.ns = ns;
    m.id = id++;
    m.type = visualization_msgs::Marker::SPHERE;
    m.action = visualization_msgs::Marker::ADD;
    m.pose.orientation.w = 1.0;
    m.pose.position = centre;
    m.scale.x = m.scale.y = m.scale.z = 2.0 * radius;
    m.color = color;
    markers.markers.push_back(m);
  };
  auto spheres = [&](const std::string& ns, size_t k, double alpha) {
    const Eigen::VectorXd q =
        Eigen::Map<const Eigen::VectorXd>(points[k].positions.data(), points[k].positions.size());
    fesd::forwardKinematics(robot, q, data);
    for (size_t s = 0; s < robot.spheres.size(); ++s) {
      sphere(ns, point(data.sphere_centres[s]), robot.spheres[s].radius, bodyColor(true, alpha));
    }
    // A free body with several spheres: each where the body is at that boundary, turned by its
    // yaw there.
    for (size_t b = 0; b < task.scene.bodies().size() && b < solution.bodies.size(); ++b) {
      const fesd_trajopt::BodyTrajectory& body = solution.bodies[b];
      if (k >= body.positions.size() || task.scene.bodies()[b].spheres.empty()) continue;
      for (const auto& [centre, radius] : bodySpheres(body, body.positions[k], yawAt(body, k))) {
        sphere(ns, centre, radius, bodyColor(false, alpha));
      }
    }
  };
  spheres("robot_start", 0, 0.9);
  spheres("robot_final", points.size() - 1, 0.5);
  for (const fesd_trajopt::SwitchEvent& event : solution.switches) {
    size_t k = 0;  // the element boundary at the switch
    while (k + 1 < solution.times.size() && solution.times[k] < event.time - 1e-12) ++k;
    spheres("robot_switch_configurations", std::min(k, points.size() - 1), 0.15);
  }
  fitToRobotScale(markers);
}

}  // namespace fesd_ros
