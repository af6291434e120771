#include "solution_message.h"

#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include "fesd_trajopt/planning/paths_around.h"
#include "robot_solution.h"

namespace fesd_ros {
namespace {

// Planar vectors are written with z = 0.
template <class XyzMessage>
XyzMessage xyz(const Eigen::VectorXd& v) {
  XyzMessage result;
  result.x = v(0);
  result.y = v(1);
  result.z = v.size() > 2 ? v(2) : 0.0;
  return result;
}

/// A pair's two names, a robot sphere first (`<link>/sphere_<k>`, then the body it touches).
std::pair<std::string, std::string> pairNames(const fesd::Scene& scene,
                                              const fesd::ContactPair& pair) {
  const auto [body, other] = scene.pairSides(pair);
  const std::vector<fesd::CollisionBody> bodies = scene.collisionBodies();
  const bool other_is_sphere =
      pair.kind == fesd::ContactPair::Kind::kBody && bodies[pair.other].sphere >= 0;
  if (bodies[pair.body].sphere < 0 && other_is_sphere) return {other, body};
  return {body, other};
}

fesd_trajopt::ContactPair pairMessage(const fesd::Scene& scene,
                                      const fesd::PairDecision& decision) {
  fesd_trajopt::ContactPair message;
  std::tie(message.first, message.second) = pairNames(scene, decision.pair);
  message.reason = decision.reason;
  message.min_distance = decision.min_distance;
  return message;
}

std_msgs::ColorRGBA color(double r, double g, double b, double a) {
  std_msgs::ColorRGBA c;
  c.r = r;
  c.g = g;
  c.b = b;
  c.a = a;
  return c;
}

}  // namespace

geometry_msgs::Point point(const Eigen::VectorXd& p) {
  return xyz<geometry_msgs::Point>(p);
}

double targetDistance(const std::vector<double>& distances, int body) {
  return body < static_cast<int>(distances.size()) ? distances[body]
                                                   : std::numeric_limits<double>::quiet_NaN();
}

fesd_trajopt::BodyTrajectory bodyTrajectory(const fesd::Scene& scene, int b,
                                            const fesd::SceneOutcome& outcome) {
  const fesd::SceneBody& body = scene.bodies()[b];
  const int dim = scene.dimension();
  fesd_trajopt::BodyTrajectory message;
  message.name = body.name;
  message.radius = body.radius;
  message.actuated = body.actuated;
  message.target_distance = targetDistance(outcome.target_distances, b);
  message.target_yaw_distance = targetDistance(outcome.target_yaw_distances, b);
  message.turning_radius = scene.turningRadius(b);
  if (b < static_cast<int>(outcome.supports.size()) && outcome.supports[b] >= 0) {
    message.support = scene.walls()[outcome.supports[b]].name;
  }
  for (const fesd::FreeBodySphere& sphere : body.spheres) {
    message.sphere_offsets.push_back(point(sphere.offset.head(dim)));
    message.sphere_radii.push_back(sphere.radius);
  }
  for (const Eigen::VectorXd& x : outcome.trajectory.states) {
    message.positions.push_back(point(x.segment(scene.stateIndex(b), dim)));
    if (body.turns) message.yaws.push_back(scene.yaw(b, x));
  }
  if (body.actuated) {
    for (const Eigen::VectorXd& u : outcome.trajectory.controls) {
      message.controls.push_back(
          xyz<geometry_msgs::Vector3>(u.segment(scene.controlIndex(b), dim)));
    }
  }
  return message;
}

std::vector<std::pair<geometry_msgs::Point, double>> bodySpheres(
    const fesd_trajopt::BodyTrajectory& body, const geometry_msgs::Point& at, double yaw) {
  if (body.sphere_offsets.empty()) return {{at, body.radius}};
  const double c = std::cos(yaw), s = std::sin(yaw);
  std::vector<std::pair<geometry_msgs::Point, double>> spheres;
  for (size_t k = 0; k < body.sphere_offsets.size(); ++k) {
    const geometry_msgs::Point& o = body.sphere_offsets[k];
    geometry_msgs::Point centre;
    centre.x = at.x + c * o.x - s * o.y;
    centre.y = at.y + s * o.x + c * o.y;
    centre.z = at.z + o.z;
    spheres.emplace_back(centre, body.sphere_radii[k]);
  }
  return spheres;
}

double yawAt(const fesd_trajopt::BodyTrajectory& body, size_t k) {
  return body.yaws.empty() ? 0.0 : body.yaws[std::min(k, body.yaws.size() - 1)];
}

std_msgs::ColorRGBA bodyColor(bool actuated, double alpha) {
  return actuated ? color(0.2, 0.45, 0.85, alpha) : color(0.95, 0.55, 0.1, alpha);
}

uint8_t statusCode(fesd::SolveStatus status) {
  using Codes = fesd_trajopt::Solution;
  switch (status) {
    case fesd::SolveStatus::kSuccess:
      return Codes::SUCCESS;
    case fesd::SolveStatus::kMaxIterations:
      return Codes::MAX_ITERATIONS;
    case fesd::SolveStatus::kInfeasible:
      return Codes::INFEASIBLE;
    case fesd::SolveStatus::kTimeout:
      return Codes::TIMEOUT;
    case fesd::SolveStatus::kComplementarityNotMet:
      return Codes::COMPLEMENTARITY_NOT_MET;
    case fesd::SolveStatus::kSolverError:
      return Codes::SOLVER_ERROR;
    case fesd::SolveStatus::kCancelled:
      return Codes::CANCELLED;
    case fesd::SolveStatus::kAccuracyNotMet:
      return Codes::ACCURACY_NOT_MET;
    case fesd::SolveStatus::kTargetNotReached:
      return Codes::TARGET_NOT_REACHED;
  }
  return Codes::SOLVER_ERROR;
}

fesd_trajopt::SwitchEvent switchMessage(const fesd::SwitchEvent& event, const std::string& first,
                                        const std::string& second) {
  fesd_trajopt::SwitchEvent message;
  message.time = event.time;
  message.first = first;
  message.second = second;
  message.kind = event.kind == fesd::SwitchEvent::Kind::kContact
                     ? fesd_trajopt::SwitchEvent::CONTACT
                     : fesd_trajopt::SwitchEvent::RELEASE;
  return message;
}

void fillAccuracy(const fesd::Scene& scene, const fesd::SceneOutcome& outcome,
                  double target_accuracy, fesd_trajopt::Solution& solution) {
  const fesd::Verification& verification = outcome.verification;
  solution.verified = outcome.verified;
  if (outcome.verified) {
    solution.verification_error = verification.error;
    solution.open_loop_error = verification.open_loop_error;
    solution.open_loop_gain = verification.open_loop_gain;
    solution.needs_feedback = target_accuracy > 0.0 && verification.error <= target_accuracy &&
                              !(verification.open_loop_error <= target_accuracy);
    for (const fesd::Graze& graze : verification.grazes) {
      fesd_trajopt::Graze message;
      std::tie(message.pair.first, message.pair.second) = pairNames(scene, graze.pair);
      message.pair.min_distance = graze.depth;
      message.interval = graze.interval;
      message.time = graze.time;
      message.depth = graze.depth;
      message.touched = graze.touched;
      solution.grazes.push_back(message);
    }
  } else {
    solution.open_loop_error = solution.open_loop_gain = std::numeric_limits<double>::quiet_NaN();
  }
  for (const fesd::AccuracyRung& rung : outcome.refinements) {
    fesd_trajopt::Refinement refinement;
    refinement.num_stages = rung.stages;
    refinement.interval_elements.assign(rung.interval_elements.begin(),
                                        rung.interval_elements.end());
    refinement.num_elements =
        rung.interval_elements.empty()
            ? 0
            : *std::max_element(rung.interval_elements.begin(), rung.interval_elements.end());
    refinement.change = rung.change;
    refinement.reason = rung.reason;
    refinement.refined_intervals.assign(rung.refined_intervals.begin(),
                                        rung.refined_intervals.end());
    refinement.error_before = rung.error_before;
    refinement.verification_error = rung.verification_error;
    refinement.grazes = rung.grazes;
    refinement.from_previous_plan = rung.from_previous_plan;
    refinement.wall_time = rung.wall_seconds;
    refinement.status = statusCode(rung.status);
    solution.refinements.push_back(refinement);
  }
}

void fillCommon(const fesd::Trajectory& trajectory, const fesd::MpccReport& report,
                fesd_trajopt::Solution& solution) {
  solution.status = statusCode(report.status);
  solution.message = report.message;
  solution.times = trajectory.times;
  for (const fesd::ElementValues& element : trajectory.elements) {
    solution.step_lengths.push_back(element.step);
  }
  solution.control_times = trajectory.interval_times;
  solution.switches_resolved = trajectory.switchesResolved();
  for (const fesd::UnresolvedSwitch& unresolved : trajectory.unresolved_switches) {
    if (solution.unresolved_elements.empty() ||
        solution.unresolved_elements.back() != static_cast<uint32_t>(unresolved.element)) {
      solution.unresolved_elements.push_back(unresolved.element);
    }
  }
  solution.state_dimension = trajectory.states.empty() ? 0 : trajectory.states.front().size();
  for (const Eigen::VectorXd& x : trajectory.states) {
    solution.states.insert(solution.states.end(), x.data(), x.data() + x.size());
  }
  fesd_trajopt::SolverStatistics& s = solution.statistics;
  s.homotopy_steps = report.history.size();
  s.ipopt_iterations = report.iterations;
  s.complementarity_residual = report.complementarity_residual;
  s.objective = report.objective;
  s.wall_time = report.wall_seconds;
  s.cpu_time = report.cpu_seconds;
  s.ipopt_time = report.ipopt_seconds;
  s.evaluation_time = report.evaluation_seconds;
  s.polished = report.polished;
  s.b_stationary = report.b_stationary;
  s.certified = report.certified;
  s.lpec_value = report.lpec_value;
  s.lpec_radius = report.lpec_radius;
  s.certificate = report.certificate;
  s.relaxed_nlps = report.relaxedNlps();
  s.branch_nlps = report.branch_nlps;
  s.lpecs = report.lpecs;
  s.lpec_time = report.lpec_seconds;
  for (const fesd::HomotopyStep& step : report.history) {
    s.sigma.push_back(step.sigma);
    s.iterations.push_back(step.iterations);
  }
}

std::vector<nav_msgs::Path> bodyPaths(const fesd_trajopt::Solution& solution) {
  std::vector<nav_msgs::Path> paths;
  for (const fesd_trajopt::BodyTrajectory& body : solution.bodies) {
    nav_msgs::Path path;
    path.header = solution.header;
    for (size_t i = 0; i < body.positions.size() && i < solution.times.size(); ++i) {
      geometry_msgs::PoseStamped pose;
      pose.header.frame_id = solution.header.frame_id;
      pose.header.stamp = solution.header.stamp + ros::Duration(solution.times[i]);
      pose.pose.position = body.positions[i];
      pose.pose.orientation.w = 1.0;
      path.poses.push_back(pose);
    }
    paths.push_back(path);
  }
  return paths;
}

namespace {

/// Each planar joint's (x, y, theta) at the element boundaries, named as MoveIt names a planar
/// joint's variables.
void addPlanarJointTrajectory(const fesd::Scene& scene, const fesd::Trajectory& trajectory,
                              const std::vector<fesd::UrdfPlanarJoint>& planar_joints,
                              trajectory_msgs::JointTrajectory& motion) {
  for (const fesd::UrdfPlanarJoint& joint : planar_joints) {
    for (const char* variable : {"/x", "/y", "/theta"}) {
      motion.joint_names.push_back(joint.joint + variable);
    }
  }
  for (size_t i = 0; i < trajectory.states.size(); ++i) {
    const Eigen::VectorXd& x = trajectory.states[i];
    trajectory_msgs::JointTrajectoryPoint point;
    for (const fesd::UrdfPlanarJoint& joint : planar_joints) {
      const int b = joint.body;
      const double yaw = scene.bodies()[b].turns ? scene.yaw(b, x) : 0.0;
      const Eigen::Vector3d values =
          fesd::planarJointValues(joint, x.segment(scene.stateIndex(b), scene.dimension()), yaw);
      point.positions.insert(point.positions.end(), values.data(), values.data() + 3);
    }
    point.time_from_start = ros::Duration(trajectory.times[i]);
    motion.points.push_back(point);
  }
}

}  // namespace

fesd_trajopt::Solution sceneSolution(const fesd::SceneTask& task, const fesd::SceneOutcome& outcome,
                                     const std::vector<fesd::UrdfPlanarJoint>& planar_joints) {
  const fesd::Scene& scene = task.scene;
  const fesd::Trajectory& trajectory = outcome.trajectory;
  const fesd::MpccReport& report = outcome.report;
  const std::vector<fesd::PairDecision>& decisions = outcome.decisions;
  fesd_trajopt::Solution solution;
  fillCommon(trajectory, report, solution);
  solution.statistics.guess_residual = outcome.guess_residual;  // NaN: no first guess
  solution.statistics.length_scale = outcome.length_scale;
  for (int b = 0; b < static_cast<int>(scene.bodies().size()); ++b) {
    solution.bodies.push_back(bodyTrajectory(scene, b, outcome));
  }
  for (const fesd::PairDecision& decision : decisions) {
    (decision.modelled  ? solution.modeled_pairs
     : decision.checked ? solution.checked_pairs
                        : solution.pruned_pairs)
        .push_back(pairMessage(scene, decision));
  }
  for (const fesd::SwitchEvent& event : trajectory.switches) {
    const auto [first, second] = pairNames(scene, outcome.modelled[event.constraint]);
    solution.switches.push_back(switchMessage(event, first, second));
  }
  if (scene.hasRobot()) addJointTrajectories(task, outcome, solution);
  if (!planar_joints.empty()) {
    addPlanarJointTrajectory(scene, trajectory, planar_joints, solution.joint_trajectory);
  }
  return solution;
}

void stackSwitchLabels(double left, double top, double line_height,
                       visualization_msgs::MarkerArray& markers) {
  int line = 0;
  for (visualization_msgs::Marker& label : markers.markers) {
    if (label.ns != "switch_labels") continue;
    // rviz centres a text on its position: half its width (about 0.4 of the height per
    // character, measured on a screenshot) right of `left` lines the labels up on the left.
    label.pose.position.x = left + 0.5 * 0.4 * label.scale.z * label.text.size();
    label.pose.position.y = top - line_height * line++;
    label.pose.position.z = 0.0;
  }
}

visualization_msgs::MarkerArray sceneMarkers(const fesd::SceneTask& task,
                                             const fesd_trajopt::Solution& solution,
                                             const std::string& frame_id,
                                             const std::vector<fesd::PushLeg>& legs,
                                             const std::vector<fesd::Transit>& transits) {
  const fesd::Scene& scene = task.scene;
  const bool planar = scene.dimension() == 2;
  visualization_msgs::MarkerArray markers;
  visualization_msgs::Marker clear;
  clear.header.frame_id = frame_id;
  clear.action = visualization_msgs::Marker::DELETEALL;
  markers.markers.push_back(clear);
  int id = 0;
  auto marker = [&](const std::string& ns, int type) {
    visualization_msgs::Marker m;
    m.header.frame_id = frame_id;
    m.header.stamp = solution.header.stamp;
    m.ns = ns;
    m.id = id++;
    m.type = type;
    m.action = visualization_msgs::Marker::ADD;
    m.pose.orientation.w = 1.0;
    return m;
  };
  auto disc = [&](const std::string& ns, const geometry_msgs::Point& at, double radius,
                  const std_msgs::ColorRGBA& c) {
    visualization_msgs::Marker m = marker(
        ns, planar ? visualization_msgs::Marker::CYLINDER : visualization_msgs::Marker::SPHERE);
    m.pose.position = at;
    m.scale.x = m.scale.y = 2.0 * radius;
    m.scale.z = planar ? 0.1 : 2.0 * radius;
    m.color = c;
    markers.markers.push_back(m);
  };
  auto body_color = [&](size_t b, double alpha) {
    return bodyColor(scene.bodies()[b].actuated, alpha);
  };
  // Lines and labels drawn for discs of radius 0.75 and more shrink with smaller spheres.
  double smallest = 0.75;
  for (const fesd_trajopt::BodyTrajectory& body : solution.bodies) {
    smallest = std::min(smallest, body.radius);
    for (double radius : body.sphere_radii) smallest = std::min(smallest, radius);
  }
  const double detail = smallest / 0.75;
  // A body as its spheres at boundary k (or at `at`, turned by `yaw`), a turning one with an
  // arrow along its heading.
  auto body_at = [&](const std::string& ns, const fesd_trajopt::BodyTrajectory& body,
                     const geometry_msgs::Point& at, double yaw, const std_msgs::ColorRGBA& c) {
    for (const auto& [centre, radius] : bodySpheres(body, at, yaw)) disc(ns, centre, radius, c);
    if (body.yaws.empty()) return;
    visualization_msgs::Marker heading = marker(ns, visualization_msgs::Marker::ARROW);
    geometry_msgs::Point tip = at;
    tip.x += body.radius * std::cos(yaw);
    tip.y += body.radius * std::sin(yaw);
    heading.points = {at, tip};
    heading.scale.x = 0.05 * body.radius;
    heading.scale.y = 0.12 * body.radius;
    heading.color = color(0.1, 0.1, 0.1, c.a);
    markers.markers.push_back(heading);
  };
  for (size_t b = 0; b < solution.bodies.size(); ++b) {
    const fesd_trajopt::BodyTrajectory& body = solution.bodies[b];
    if (body.positions.empty()) continue;
    body_at("bodies_start", body, body.positions.front(), yawAt(body, 0), body_color(b, 1.0));
    body_at("bodies_final", body, body.positions.back(), yawAt(body, body.positions.size() - 1),
            body_color(b, 0.6));
    const fesd::BodyTask& t = task.bodies[b];
    if (t.hasTarget() || t.hasYawTarget()) {  // a yaw alone: drawn where the body ends
      body_at("targets", body, t.hasTarget() ? point(t.target) : body.positions.back(),
              t.hasYawTarget() ? t.target_yaw : yawAt(body, 0), color(0.2, 0.8, 0.3, 0.3));
    }
    visualization_msgs::Marker path = marker("paths", visualization_msgs::Marker::LINE_STRIP);
    path.points = body.positions;
    path.scale.x = 0.08 * detail;
    path.color = body_color(b, 1.0);
    markers.markers.push_back(path);
  }
  // The switch labels in a column right of everything drawn, one line each in time order: over
  // the bodies they would hide the plan (sixteen stacked over the push-T).
  double right = -INFINITY, top = -INFINITY;
  auto extend = [&](const geometry_msgs::Point& p, double radius) {
    right = std::max(right, p.x + radius);
    top = std::max(top, p.y + radius);
  };
  for (const fesd_trajopt::BodyTrajectory& body : solution.bodies) {
    for (const geometry_msgs::Point& p : body.positions) extend(p, body.radius);
  }
  for (size_t b = 0; b < task.bodies.size() && b < scene.bodies().size(); ++b) {
    if (task.bodies[b].hasTarget()) extend(point(task.bodies[b].target), scene.bodies()[b].radius);
  }
  for (const fesd::SceneObstacle& o : scene.obstacles()) extend(point(o.position), o.radius);
  for (const fesd_trajopt::SwitchEvent& event : solution.switches) {
    // The configuration at the switch: the element boundary at that time.
    size_t k = 0;
    while (k + 1 < solution.times.size() && solution.times[k] < event.time - 1e-12) ++k;
    for (size_t b = 0; b < solution.bodies.size(); ++b) {
      body_at("switch_configurations", solution.bodies[b], solution.bodies[b].positions[k],
              yawAt(solution.bodies[b], k), body_color(b, 0.15));
    }
    visualization_msgs::Marker label =
        marker("switch_labels", visualization_msgs::Marker::TEXT_VIEW_FACING);
    char text[160];
    std::snprintf(text, sizeof(text), "t=%.3f %s %s/%s", event.time,
                  event.kind == fesd_trajopt::SwitchEvent::CONTACT ? "contact" : "release",
                  event.first.c_str(), event.second.c_str());
    label.text = text;
    label.scale.z = 0.6 * detail;
    label.color = color(0.1, 0.1, 0.1, 1.0);  // for the light background of the shipped view
    markers.markers.push_back(label);
  }
  stackSwitchLabels(right + 0.8 * detail, top, 0.8 * detail, markers);
  for (const fesd::SceneObstacle& o : scene.obstacles()) {
    disc("obstacles", point(o.position), o.radius, color(0.5, 0.5, 0.5, 1.0));
  }
  for (const fesd::PushLeg& leg : legs) {
    Eigen::VectorXd from = leg.from;
    if (!leg.through.empty()) {  // the turning push along its rounded corners, the arrow at its end
      const fesd::RoundedPath path = fesd::roundedPush(leg);
      visualization_msgs::Marker line = marker("plan_legs", visualization_msgs::Marker::LINE_STRIP);
      constexpr int kSamples = 40;
      for (int k = 0; k <= kSamples; ++k) {
        line.points.push_back(point(path.at(path.length() * k / kSamples)));
      }
      line.scale.x = 0.12 * detail;
      line.color = color(0.9, 0.5, 0.1, 0.8);
      markers.markers.push_back(line);
      from = path.at(path.length() - std::min(path.length(), (leg.to - leg.through.back()).norm()));
    }
    visualization_msgs::Marker arrow = marker("plan_legs", visualization_msgs::Marker::ARROW);
    arrow.points = {point(from), point(leg.to)};
    arrow.scale.x = 0.12 * detail;  // shaft and head diameters, head length
    arrow.scale.y = 0.35 * detail;
    arrow.scale.z = 0.4 * detail;
    arrow.color = color(0.9, 0.5, 0.1, 0.8);
    markers.markers.push_back(arrow);
  }
  for (const fesd::Transit& transit : transits) {
    // Dashed: every other piece of the path cut into pieces of about 0.25 (scaled).
    visualization_msgs::Marker dashes =
        marker("plan_transits", visualization_msgs::Marker::LINE_LIST);
    const double length = fesd::pathLength(transit.path);
    const int pieces = 2 * std::max(1, static_cast<int>(length / (0.25 * detail)));
    for (int k = 0; k < pieces; k += 2) {
      dashes.points.push_back(point(fesd::pointAlong(transit.path, double(k) / pieces)));
      dashes.points.push_back(point(fesd::pointAlong(transit.path, double(k + 1) / pieces)));
    }
    dashes.scale.x = 0.05 * detail;
    dashes.color = bodyColor(true, 0.8);
    markers.markers.push_back(dashes);
  }
  for (const fesd::SceneWall& w : scene.walls()) {
    // A thin plate through the wall's closest point to the origin, its x axis along the normal.
    visualization_msgs::Marker plate = marker("walls", visualization_msgs::Marker::CUBE);
    const Eigen::Vector3d normal =
        planar ? Eigen::Vector3d(w.normal(0), w.normal(1), 0.0) : Eigen::Vector3d(w.normal);
    const Eigen::Vector3d at = normal * w.offset;
    plate.pose.position.x = at.x();
    plate.pose.position.y = at.y();
    plate.pose.position.z = at.z();
    const Eigen::Quaterniond q =
        Eigen::Quaterniond::FromTwoVectors(Eigen::Vector3d::UnitX(), normal);
    plate.pose.orientation.x = q.x();
    plate.pose.orientation.y = q.y();
    plate.pose.orientation.z = q.z();
    plate.pose.orientation.w = q.w();
    plate.scale.x = 0.1;
    plate.scale.y = 60.0;
    plate.scale.z = planar ? 0.2 : 60.0;
    plate.color = color(0.6, 0.2, 0.2, 0.8);
    markers.markers.push_back(plate);
  }
  if (task.scene.hasRobot()) addRobotMarkers(task, solution, frame_id, markers);
  return markers;
}

}  // namespace fesd_ros
