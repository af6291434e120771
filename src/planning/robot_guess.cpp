#include "fesd_trajopt/planning/robot_guess.h"

#include <algorithm>
#include <limits>
#include <optional>

#include <Eigen/Geometry>

#include "fesd_trajopt/kinematics/body_clearance.h"
#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "fesd_trajopt/kinematics/inverse_kinematics.h"
#include "fesd_trajopt/planning/bounding_discs.h"
#include "fesd_trajopt/planning/push_plan.h"
#include "fesd_trajopt/scene/collision_centres.h"

namespace fesd {
namespace {

/// The first passive free body with a weighted target, -1 if none.
int pushedBody(const SceneTask& task) {
  const Scene& scene = task.scene;
  for (size_t b = 0; b < scene.bodies().size(); ++b) {
    const BodyTask& t = task.bodies[b];
    if (!scene.bodies()[b].actuated && t.hasTarget()) {
      return static_cast<int>(b);
    }
  }
  return -1;
}

Eigen::Vector3d padded(const Eigen::VectorXd& v) {
  Eigen::Vector3d p = Eigen::Vector3d::Zero();
  p.head(v.size()) = v;
  return p;
}

/// The push plan of the sphere as a disc pushing the body among the obstacles and walls.
PushPlan proxyPlan(const SceneTask& task, int sphere, int body, const Eigen::Vector3d& start) {
  const Scene& scene = task.scene;
  const int dim = scene.dimension();
  SceneTask proxy;
  proxy.scene = Scene(dim);
  const KinematicSphere& s = scene.robot().spheres[sphere];
  proxy.scene.bodies().push_back({s.name, s.radius, start.head(dim), true});
  // The body as its bounding disc (the planner plans discs): the proxy's pairs begin with the
  // one between the sphere's disc and it.
  proxy.scene.bodies().push_back(boundingDisc(scene.bodies()[body]));
  proxy.scene.bodies().back().actuated = false;
  proxy.scene.obstacles() = scene.obstacles();
  proxy.scene.walls() = scene.walls();
  proxy.bodies.resize(2);
  // The sphere's speed in the scene is the joints' doing, not one bound: no time limit here.
  proxy.bodies[0].max_speed = std::numeric_limits<double>::infinity();
  proxy.bodies[1] = task.bodies[body];
  proxy.horizon = task.horizon;
  proxy.num_intervals = task.num_intervals;
  proxy.control_weight = task.control_weight;
  return planPushes(proxy, proxy.scene.allPairs());
}

/// The sphere's push plan in the plane of the table a turning body with a yaw target slides on:
/// the turning push planner's, with the sphere as a disc and the body's spheres in the plane (its
/// pairs: the disc with each sphere, in order). None where that planner has none (obstacles,
/// walls besides level ones, other bodies, no plan of its shapes): the bounding disc's then.
std::optional<PushPlan> planOnTheTable(const SceneTask& task, int sphere, int body,
                                       const Eigen::Vector3d& start) {
  const Scene& scene = task.scene;
  const SceneBody& pushed = scene.bodies()[body];
  bool level = true;
  for (int w = 0; w < static_cast<int>(scene.walls().size()); ++w)
    level = level && scene.isLevel(w);
  if (scene.dimension() != 3 || !pushed.turns || !task.bodies[body].hasYawTarget() ||
      scene.supportOf(body) < 0 || !level || !scene.obstacles().empty() ||
      scene.bodies().size() != 1) {
    return std::nullopt;
  }
  SceneTask plane;
  plane.scene = Scene(2);
  plane.scene.bodies().push_back({scene.robot().spheres[sphere].name,
                                  scene.robot().spheres[sphere].radius, start.head<2>(), true});
  SceneBody flat = pushed;
  flat.position = pushed.position.head<2>();
  for (FreeBodySphere& s : flat.spheres) s.offset.z() = 0.0;
  plane.scene.bodies().push_back(flat);
  plane.bodies = {BodyTask{}, task.bodies[body]};
  // The sphere's speed in the scene is the joints' doing, not one bound.
  plane.bodies[0].max_speed = std::numeric_limits<double>::infinity();
  plane.bodies[1].target = task.bodies[body].target.head<2>();
  plane.horizon = task.horizon;
  plane.num_intervals = task.num_intervals;
  plane.control_weight = task.control_weight;
  PushPlan plan = planPushes(plane, plane.scene.allPairs());
  if (!plan.turns_bodies) return std::nullopt;
  return plan;
}

/// The collision body of the pushed body that the proxy's push touches: of a body with several
/// spheres, the one whose surface is nearest the pushing disc at the contact time.
int touchedCollisionBody(const Scene& scene, int body, const PushPlan& plan) {
  const std::vector<int> candidates = scene.freeBodyCollisionBodies(body);
  if (candidates.size() == 1) return candidates.front();
  const int dim = scene.dimension();
  const Eigen::VectorXd at = plan.guess.state(plan.contact_time);
  int nearest = candidates.front();
  double nearest_gap = std::numeric_limits<double>::infinity();
  // The plan moves the body without turning it: its spheres stay at the start yaw.
  const SceneBody& pushed = scene.bodies()[body];
  for (int c : candidates) {
    const CollisionBody& sphere = scene.collisionBodies()[c];
    Eigen::VectorXd offset = sphere.centre.offset.head(dim);
    if (pushed.turns) offset.head<2>() = Eigen::Rotation2Dd(pushed.yaw) * offset.head<2>();
    const double gap = (at.segment(dim, dim) + offset - at.head(dim)).norm() - sphere.radius;
    if (gap < nearest_gap) {
      nearest = c;
      nearest_gap = gap;
    }
  }
  return nearest;
}

/// Linear interpolation of boundary values at times horizon * k / (n - 1).
Eigen::VectorXd interpolate(const std::vector<Eigen::VectorXd>& values, double horizon, double t) {
  const int n = static_cast<int>(values.size());
  const double position = std::clamp(t / horizon, 0.0, 1.0) * (n - 1);
  const int k = std::min(static_cast<int>(position), n - 2);
  const double fraction = position - k;
  return (1.0 - fraction) * values[k] + fraction * values[k + 1];
}

}  // namespace

int pushingSphere(const SceneTask& task, int pushed_body) {
  const auto passive = [](const JointTask& joint) { return joint.passive; };
  if (std::all_of(task.joints.begin(), task.joints.end(), passive)) return -1;
  const KinematicModel& robot = task.scene.robot();
  int tool_joint = -1;
  for (const KinematicSphere& s : robot.spheres)
    tool_joint = std::max(tool_joint, robot.links[s.link].joint);
  const SceneBody& body = task.scene.bodies().at(pushed_body);
  const BodyTask& t = task.bodies.at(pushed_body);
  Eigen::Vector3d direction = padded(t.target) - padded(body.position);
  if (direction.norm() > 0.0) direction.normalize();
  KinematicData data;
  forwardKinematics(robot, task.scene.initialJoints(), data);
  int best = -1;
  double best_distance = 0.0;
  for (int s = 0; s < static_cast<int>(robot.spheres.size()); ++s) {
    if (robot.links[robot.spheres[s].link].joint != tool_joint) continue;
    const Eigen::Vector3d approach =
        padded(body.position) - (boundingRadius(body) + robot.spheres[s].radius) * direction;
    Eigen::Vector3d centre = data.sphere_centres[s];
    if (task.scene.dimension() == 2) centre.z() = 0.0;
    const double distance = (centre - approach).norm();
    if (best < 0 || distance < best_distance) {
      best = s;
      best_distance = distance;
    }
  }
  return best;
}

RobotGuess planRobotGuess(const SceneTask& task, const std::vector<ContactPair>& pairs,
                          int elements_per_interval) {
  const Scene& scene = task.scene;
  const int nq = scene.numJoints();
  const int boundaries = task.num_intervals * elements_per_interval + 1;
  RobotGuess result;
  result.pushed_body = pushedBody(task);
  if (result.pushed_body >= 0) result.pusher_sphere = pushingSphere(task, result.pushed_body);
  const double horizon = task.horizon;
  const Eigen::VectorXd x0 = scene.initialState();
  if (result.pusher_sphere < 0) {
    // Nothing to push: the joints move straight to their targets.
    Eigen::VectorXd end = scene.initialJoints();
    for (int j = 0; j < nq; ++j) {
      if (task.joints[j].target_weight > 0.0 && !task.joints[j].passive) {
        end(j) = task.joints[j].target;
      }
    }
    for (int k = 0; k < boundaries; ++k) {
      const double fraction = static_cast<double>(k) / (boundaries - 1);
      result.boundary_joints.push_back((1.0 - fraction) * scene.initialJoints() + fraction * end);
    }
  } else {
    KinematicData data;
    forwardKinematics(scene.robot(), scene.initialJoints(), data);
    const Eigen::Vector3d start = data.sphere_centres[result.pusher_sphere];
    const int body = result.pushed_body, dim = scene.dimension();
    const std::optional<PushPlan> on_table =
        planOnTheTable(task, result.pusher_sphere, body, start);
    const PushPlan plan = on_table ? *on_table : proxyPlan(task, result.pusher_sphere, body, start);
    result.turns_bodies = on_table.has_value();
    // The plan's state: the sphere's disc, then the body (on the table: in its plane, turning).
    const int plan_dim = on_table ? 2 : dim;
    Eigen::VectorXd q = scene.initialJoints();
    InverseKinematicsOptions ik;
    for (const JointTask& joint : task.joints) ik.held.push_back(joint.passive);
    const int first = scene.stateIndex(body);
    // The pushed body's spheres where the plan has them at t: the guess touches the body with the
    // pusher only, so the arm's other spheres are kept out of them (out, not a margin away: with
    // a margin the planar arm's turning bar got far slower or missed its target; results.md).
    const std::vector<int> body_spheres = scene.freeBodyCollisionBodies(body);
    const std::vector<CollisionBody> collision_bodies = scene.collisionBodies();
    SpheresToClear clear;
    clear.planar = dim == 2;
    for (int c : body_spheres) clear.radii.push_back(collision_bodies[c].radius);
    CentreEvaluator evaluator(scene.robotPointer(), dim);
    const auto bodySpheres = [&](double t) {
      Eigen::VectorXd x = x0;
      const Eigen::VectorXd planned = plan.guess.state(t);
      if (on_table) {
        x.segment<2>(first) = planned.segment<2>(2);
        x(first + dim) = planned(4);
      } else {
        x.segment(first, dim) = planned.segment(dim, dim);
      }
      evaluator.setState(x.data());
      std::vector<Eigen::Vector3d> centres;
      for (int c : body_spheres) centres.push_back(evaluator.position(collision_bodies[c].centre));
      return centres;
    };
    for (int k = 0; k < boundaries; ++k) {
      const double t = horizon * k / (boundaries - 1);
      Eigen::Vector3d target = start;  // planar: keep the sphere's own z
      target.head(plan_dim) = plan.guess.state(t).head(plan_dim);
      // On the table the sphere pushes at the height of the body's centre: level, no lift.
      if (on_table) target.z() = scene.bodies()[body].position(2);
      if (k > 0) {
        q = sphereInverseKinematics(scene.robot(), result.pusher_sphere, target, q, ik).q;
        clear.centres = bodySpheres(t);
        q = clearOfSpheres(scene.robot(), result.pusher_sphere, target, q, clear, ik);
      }
      result.boundary_joints.push_back(q);
    }
    const auto plan_state = plan.guess.state;
    const auto plan_multipliers = plan.guess.multipliers;
    // Where each of the plan's pairs is in `pairs`: on the table the disc with each of the
    // body's spheres, else its only body pair, the disc with the body's sphere it touches.
    const int pusher = scene.sphereBody(result.pusher_sphere);
    std::vector<int> touched = scene.freeBodyCollisionBodies(body);
    if (!on_table) touched = {touchedCollisionBody(scene, body, plan)};
    std::vector<int> rows;
    for (int c : touched) {
      const auto found =
          std::find(pairs.begin(), pairs.end(), ContactPair{c, ContactPair::Kind::kBody, pusher});
      rows.push_back(found == pairs.end() ? -1 : static_cast<int>(found - pairs.begin()));
    }
    const int num_pairs = static_cast<int>(pairs.size());
    result.guess.multipliers = [plan_multipliers, rows, num_pairs](double t) {
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(num_pairs);
      if (!plan_multipliers) return lambda;
      const Eigen::VectorXd planned = plan_multipliers(t);
      for (size_t k = 0; k < rows.size() && static_cast<int>(k) < planned.size(); ++k) {
        if (rows[k] >= 0) lambda(rows[k]) = planned(k);
      }
      return lambda;
    };
    const std::vector<Eigen::VectorXd> joints = result.boundary_joints;
    const bool turning = on_table.has_value();
    result.guess.state = [x0, joints, horizon, plan_state, first, dim, nq, turning](double t) {
      Eigen::VectorXd x = x0;
      x.head(nq) = interpolate(joints, horizon, t);
      const Eigen::VectorXd planned = plan_state(t);
      if (turning) {  // x, y and s = rho yaw; the height stays
        x.segment<2>(first) = planned.segment<2>(2);
        x(first + dim) = planned(4);
      } else {
        x.segment(first, dim) = planned.segment(dim, dim);
      }
      return x;
    };
  }
  if (!result.guess.state) {
    const std::vector<Eigen::VectorXd> joints = result.boundary_joints;
    result.guess.state = [x0, joints, horizon, nq](double t) {
      Eigen::VectorXd x = x0;
      x.head(nq) = interpolate(joints, horizon, t);
      return x;
    };
  }
  const double step = horizon / task.num_intervals;
  for (int i = 0; i < task.num_intervals; ++i) {
    Eigen::VectorXd u = Eigen::VectorXd::Zero(scene.controlSize());
    const Eigen::VectorXd motion = result.boundary_joints[(i + 1) * elements_per_interval] -
                                   result.boundary_joints[i * elements_per_interval];
    for (int j = 0; j < nq; ++j) {
      const double limit = jointSpeedLimit(task, j);
      u(j) = std::clamp(motion(j) / step, -limit, limit);
    }
    result.guess.controls.push_back(u);
  }
  return result;
}

}  // namespace fesd
