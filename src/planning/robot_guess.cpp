#include "fesd_trajopt/planning/robot_guess.h"

#include <algorithm>
#include <limits>

#include <Eigen/Geometry>

#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "fesd_trajopt/kinematics/inverse_kinematics.h"
#include "fesd_trajopt/planning/bounding_discs.h"
#include "fesd_trajopt/planning/push_plan.h"

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
    const PushPlan plan = proxyPlan(task, result.pusher_sphere, result.pushed_body, start);
    Eigen::VectorXd q = scene.initialJoints();
    InverseKinematicsOptions ik;
    for (const JointTask& joint : task.joints) ik.held.push_back(joint.passive);
    for (int k = 0; k < boundaries; ++k) {
      const double t = horizon * k / (boundaries - 1);
      Eigen::Vector3d target = start;  // planar: keep the sphere's own z
      target.head(scene.dimension()) = plan.guess.state(t).head(scene.dimension());
      if (k > 0) q = sphereInverseKinematics(scene.robot(), result.pusher_sphere, target, q, ik).q;
      result.boundary_joints.push_back(q);
    }
    const int body = result.pushed_body, dim = scene.dimension();
    const int first = scene.stateIndex(body);
    const auto plan_state = plan.guess.state;
    const auto plan_multipliers = plan.guess.multipliers;
    const ContactPair contact{touchedCollisionBody(scene, body, plan), ContactPair::Kind::kBody,
                              scene.sphereBody(result.pusher_sphere)};
    const auto found = std::find(pairs.begin(), pairs.end(), contact);
    const int contact_index = found == pairs.end() ? -1 : static_cast<int>(found - pairs.begin());
    const int num_pairs = static_cast<int>(pairs.size());
    result.guess.multipliers = [plan_multipliers, contact_index, num_pairs](double t) {
      Eigen::VectorXd lambda = Eigen::VectorXd::Zero(num_pairs);
      // The proxy's pairs begin with its only body pair: the sphere's disc and the body.
      if (contact_index >= 0 && plan_multipliers) lambda(contact_index) = plan_multipliers(t)(0);
      return lambda;
    };
    const std::vector<Eigen::VectorXd> joints = result.boundary_joints;
    result.guess.state = [x0, joints, horizon, plan_state, first, dim, nq](double t) {
      Eigen::VectorXd x = x0;
      x.head(nq) = interpolate(joints, horizon, t);
      x.segment(first, dim) = plan_state(t).segment(dim, dim);
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
