#pragma once

#include <fesd_trajopt/Solution.h>
#include <nav_msgs/Path.h>
#include <visualization_msgs/MarkerArray.h>

#include "fesd_trajopt/discretization/trajectory.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "fesd_trajopt/scene/urdf_scene.h"
#include "fesd_trajopt/solver/mpcc_solver.h"

namespace fesd_ros {

/// The status constant (Solution.msg's) of a solver outcome.
uint8_t statusCode(fesd::SolveStatus status);
constexpr uint8_t kInvalidRequest = fesd_trajopt::Solution::INVALID_REQUEST;

/// An answer (service response or action result) without a solve: the status and why, also in
/// its solution.
template <class Answer>
void setUnsolved(Answer& answer, uint8_t status, const std::string& message) {
  answer.status = answer.solution.status = status;
  answer.message = answer.solution.message = message;
}

/// The Solution message of a scene task's outcome: times, each body's positions, controls and
/// distance from its target, the full state, switches and pair decisions (named by the pairs'
/// sides, a robot sphere `<link>/sphere_<k>` first), statistics; with a robot its
/// joint_trajectory and joint_commands (addJointTrajectories), else the URDF's planar joints'
/// coordinates in joint_trajectory.
fesd_trajopt::Solution sceneSolution(const fesd::SceneTask& task, const fesd::SceneOutcome& outcome,
                                     const std::vector<fesd::UrdfPlanarJoint>& planar_joints);

/// A point from a planar (z = 0) or spatial vector.
geometry_msgs::Point point(const Eigen::VectorXd& p);

/// A body's distance from its target, NaN when it has none (or the outcome was not judged).
double targetDistance(const std::vector<double>& distances, int body);

/// Body b's part of a solution: name, radius, role, spheres, distances from its targets
/// (position, yaw), positions (and a turning body's yaws) at the element boundaries and, if
/// actuated, its controls.
fesd_trajopt::BodyTrajectory bodyTrajectory(const fesd::Scene& scene, int b,
                                            const fesd::SceneOutcome& outcome);

/// A body's collision spheres with it at `at` and turned by `yaw` about z (itself when it is one
/// sphere): (centre, radius) each, for rviz.
std::vector<std::pair<geometry_msgs::Point, double>> bodySpheres(
    const fesd_trajopt::BodyTrajectory& body, const geometry_msgs::Point& at, double yaw);
/// A body's yaw at element boundary k (0 for one that does not turn).
double yawAt(const fesd_trajopt::BodyTrajectory& body, size_t k);

/// The parts every solution has: times, steps, full states, statistics.
void fillCommon(const fesd::Trajectory& trajectory, const fesd::MpccReport& report,
                fesd_trajopt::Solution& solution);

/// A switch event of the plan between two named sides (a pair's).
fesd_trajopt::SwitchEvent switchMessage(const fesd::SwitchEvent& event, const std::string& first,
                                        const std::string& second);

/// The verification (interval errors, open loop, grazes) and the accuracy ladder's rungs of a
/// plan; needs_feedback when its open-loop error exceeds `target_accuracy` (> 0).
void fillAccuracy(const fesd::Scene& scene, const fesd::SceneOutcome& outcome,
                  double target_accuracy, fesd_trajopt::Solution& solution);

/// rviz colour of a body: actuated blue, passive orange.
std_msgs::ColorRGBA bodyColor(bool actuated, double alpha);

/// One nav_msgs/Path per body of a solution (in its order): the positions at the element
/// boundaries, stamped with the solution's stamp plus their time, in the solution's frame.
std::vector<nav_msgs::Path> bodyPaths(const fesd_trajopt::Solution& solution);

/// The switch labels (namespace switch_labels, in time order) in a column: left-aligned at x =
/// `left`, from y = `top` down, one `line_height` apart (beside the scene, not over it).
void stackSwitchLabels(double left, double top, double line_height,
                       visualization_msgs::MarkerArray& markers);

/// rviz markers of a scene solution, one namespace per layer (bodies_start, bodies_final,
/// targets, paths, switch_configurations, switch_labels, obstacles, walls), preceded by a
/// DELETEALL; with a robot, its spheres too (addRobotMarkers); with a push plan, its legs (arrows,
/// plan_legs) and its pushers' transits (dashed lines, plan_transits).
visualization_msgs::MarkerArray sceneMarkers(const fesd::SceneTask& task,
                                             const fesd_trajopt::Solution& solution,
                                             const std::string& frame_id,
                                             const std::vector<fesd::PushLeg>& legs = {},
                                             const std::vector<fesd::Transit>& transits = {});

}  // namespace fesd_ros
