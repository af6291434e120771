#include "fesd_trajopt/scene/scene_task.h"

#include <algorithm>
#include <cmath>
#include <set>
#include <sstream>
#include <tuple>

#include <Eigen/Geometry>

#include "fesd_trajopt/function/quadratic_function.h"
#include "fesd_trajopt/kinematics/reach.h"
#include "fesd_trajopt/nlp/nlp_assembly.h"

namespace fesd {
namespace {

constexpr double kInf = NlpAssembly::kInfinity;

bool finite(const Eigen::VectorXd& v) {
  return v.allFinite();
}

std::string vectorProblem(const Eigen::VectorXd& v, int dimension, double max_coordinate) {
  if (v.size() != dimension) {
    return "has " + std::to_string(v.size()) + " coordinates, the scene " +
           std::to_string(dimension);
  }
  if (!finite(v)) return "is not finite";
  if (v.cwiseAbs().maxCoeff() > max_coordinate) return "is beyond the coordinate limit";
  return "";
}

/// Bounds that are either empty or one per coordinate, not NaN, lower <= upper.
std::string boundsProblem(const Eigen::VectorXd& lower, const Eigen::VectorXd& upper,
                          int dimension) {
  for (const Eigen::VectorXd* b : {&lower, &upper}) {
    if (b->size() != 0 && b->size() != dimension) return "have the wrong number of coordinates";
    if (b->size() != 0 && b->hasNaN()) return "contain NaN";
  }
  if (lower.size() && upper.size() && (lower.array() > upper.array()).any()) {
    return "are contradictory (lower > upper)";
  }
  return "";
}

/// Per coordinate: where a point fixed to a free body (its position plus `offset`: a sphere's
/// centre, or the position itself) can be during the task (start +- reach, within the workspace).
struct Box {
  Eigen::VectorXd low, high;
};

Box reachableBox(const SceneTask& task, int free_body, const Eigen::Vector3d& offset3,
                 double reach) {
  const SceneBody& body = task.scene.bodies()[free_body];
  const int dim = task.scene.dimension();
  Eigen::VectorXd offset = offset3.head(dim);                         // at the start
  Eigen::VectorXd clip = offset, slack = Eigen::VectorXd::Zero(dim);  // within the workspace
  if (body.turns) {  // turned by the start yaw, and anywhere on its circle later
    offset.head<2>() = Eigen::Rotation2Dd(body.yaw) * offset3.head<2>();
    clip.head<2>().setZero();
    slack.head<2>().setConstant(offset3.head<2>().norm());
  }
  const Eigen::VectorXd centre = body.position + offset;
  const BodyTask& t = task.bodies[free_body];
  Box box{centre.array() - reach, centre.array() + reach};
  if (t.workspace_lower.size()) box.low = box.low.cwiseMax(t.workspace_lower + clip - slack);
  if (t.workspace_upper.size()) box.high = box.high.cwiseMin(t.workspace_upper + clip + slack);
  return box;
}

/// Smallest distance between points of two boxes.
double boxDistance(const Box& a, const Box& b) {
  const Eigen::ArrayXd gap =
      (a.low.array() - b.high.array()).max(b.low.array() - a.high.array()).max(0.0);
  return std::sqrt(gap.square().sum());
}

std::string formatNumber(double value) {
  std::ostringstream out;
  out.precision(3);
  out << value;
  return out.str();
}

/// A lower bound on the gap between a pair's surfaces during the task, each side within its
/// reach of its start: boxes for free bodies (within their workspaces), balls for robot spheres.
double separationBound(const SceneTask& task, const std::vector<CollisionBody>& bodies,
                       const ContactPair& pair, const std::vector<double>& reach) {
  const Scene& scene = task.scene;
  const CollisionBody& a = bodies[pair.body];
  const bool two_free =
      a.sphere < 0 && (pair.kind != ContactPair::Kind::kBody || bodies[pair.other].sphere < 0);
  if (!two_free) {
    const double other = pair.kind == ContactPair::Kind::kBody ? reach[pair.other] : 0.0;
    return scene.pairGap(pair, scene.initialState()) - reach[pair.body] - other;
  }
  const Box box = reachableBox(task, a.free_body, a.centre.offset, reach[pair.body]);
  switch (pair.kind) {
    case ContactPair::Kind::kBody: {
      const CollisionBody& b = bodies[pair.other];
      return boxDistance(box, reachableBox(task, b.free_body, b.centre.offset, reach[pair.other])) -
             a.radius - b.radius;
    }
    case ContactPair::Kind::kObstacle: {
      const SceneObstacle& o = scene.obstacles()[pair.other];
      return boxDistance(box, Box{o.position, o.position}) - a.radius - o.radius;
    }
    case ContactPair::Kind::kWall: {
      const SceneWall& w = scene.walls()[pair.other];
      return (w.normal.array() * box.low.array()).min(w.normal.array() * box.high.array()).sum() -
             w.offset - a.radius;
    }
  }
  return 0.0;
}

/// |u_max| over every control coordinate at its bound.
double controlNorm(const SceneTask& task) {
  const Scene& scene = task.scene;
  double squared = 0.0;
  for (int j = 0; j < scene.numJoints(); ++j) {
    squared += jointSpeedLimit(task, j) * jointSpeedLimit(task, j);
  }
  for (size_t b = 0; b < scene.bodies().size(); ++b) {
    if (scene.bodies()[b].actuated) {
      squared += scene.dimension() * task.bodies[b].max_speed * task.bodies[b].max_speed;
    }
  }
  return std::sqrt(squared);
}

std::string gridProblem(double horizon, int num_intervals, double control_weight,
                        const TaskLimits& limits) {
  if (!(horizon > 0.0) || !std::isfinite(horizon) || horizon > limits.max_horizon) {
    return "the horizon must be in (0, " + formatNumber(limits.max_horizon) + "], got " +
           formatNumber(horizon);
  }
  if (num_intervals < 1 || num_intervals > limits.max_intervals) {
    return "the number of control intervals must be in 1.." + std::to_string(limits.max_intervals) +
           ", got " + std::to_string(num_intervals);
  }
  if (!(control_weight >= 0.0) || !std::isfinite(control_weight)) {
    return "the control weight must be finite and >= 0";
  }
  return "";
}

std::string bodiesProblem(const Scene& scene, const std::vector<BodyTask>& bodies,
                          const TaskLimits& limits) {
  const int dim = scene.dimension();
  std::set<std::string> names;
  for (size_t b = 0; b < scene.bodies().size(); ++b) {
    const SceneBody& body = scene.bodies()[b];
    const BodyTask& t = bodies[b];
    const std::string who = "body '" + body.name + "'";
    if (!names.insert(body.name).second) return "two bodies are named '" + body.name + "'";
    if (!(body.radius > 0.0) || !std::isfinite(body.radius)) {
      return who + " has radius " + formatNumber(scene.userLength(body.radius)) +
             " (must be > 0 and finite)";
    }
    std::string problem = vectorProblem(body.position, dim, limits.max_coordinate);
    if (!problem.empty()) return who + ": the initial position " + problem;
    if (!(t.max_speed >= 0.0) || !std::isfinite(t.max_speed)) {
      return who + ": the speed bound must be finite and >= 0";
    }
    if (t.target.size()) {
      problem = vectorProblem(t.target, dim, limits.max_coordinate);
      if (!problem.empty()) return who + ": the target " + problem;
    }
    if (!(t.target_weight >= 0.0) || !std::isfinite(t.target_weight)) {
      return who + ": the target weight must be finite and >= 0";
    }
    if (t.target_weight > 0.0 && t.target.size() == 0) return who + " has a weight but no target";
    problem = turningBodyProblem(body);
    if (!problem.empty()) return who + " " + problem;
    if (!(std::fabs(t.target_yaw) <= 1e4) || !(t.target_yaw_weight >= 0.0) ||
        !std::isfinite(t.target_yaw_weight)) {
      return who + ": the target yaw (within 1e4 rad) and its weight must be finite (weight >= 0)";
    }
    if (t.target_yaw_weight > 0.0 && !body.turns)
      return who + " has a target yaw but does not turn";
  }
  return "";
}

/// A support that cannot hold its body: named in a planar scene, no wall, not level or not under
/// the body; or two level walls a body rests on without a name for either.
std::string supportProblem(const Scene& scene) {
  for (int b = 0; b < static_cast<int>(scene.bodies().size()); ++b) {
    const SceneBody& body = scene.bodies()[b];
    const std::string who = "body '" + body.name + "'";
    if (body.support == SupportMode::kWall) {
      const int w = body.support_wall;
      if (scene.dimension() != 3) {
        return who + ": supports are for spatial scenes (planar bodies move in their plane)";
      }
      if (w < 0 || w >= static_cast<int>(scene.walls().size())) {
        return who + ": its support is no wall of the scene";
      }
      const std::string wall = "'" + scene.walls()[w].name + "'";
      if (!scene.isLevel(w)) {
        return who + " cannot slide on " + wall + ": a support must be level (normal along z)";
      }
      const auto [gap, radius] = scene.lowestGap(b, w);
      if (std::fabs(gap) > kRestingTolerance * radius) {
        return who + " does not rest on " + wall + ": its lowest sphere is " +
               formatNumber(scene.userLength(gap)) + " from it";
      }
    } else if (body.support == SupportMode::kAuto) {
      const std::vector<int> resting = scene.restingWalls(b);
      if (resting.size() > 1) {
        return who + " rests on two level walls, '" + scene.walls()[resting[0]].name + "' and '" +
               scene.walls()[resting[1]].name + "': name its support, or let it float";
      }
    }
  }
  return "";
}

std::string fixedGeometryProblem(const Scene& scene, const TaskLimits& limits) {
  const int dim = scene.dimension();
  for (const SceneObstacle& o : scene.obstacles()) {
    if (!(o.radius > 0.0) || !std::isfinite(o.radius)) {
      return "obstacle '" + o.name + "' has radius " + formatNumber(scene.userLength(o.radius)) +
             " (must be > 0 and finite)";
    }
    const std::string problem = vectorProblem(o.position, dim, limits.max_coordinate);
    if (!problem.empty()) return "obstacle '" + o.name + "': the position " + problem;
  }
  for (const SceneWall& w : scene.walls()) {
    if (w.normal.size() != dim || !finite(w.normal) || std::fabs(w.normal.norm() - 1.0) > 1e-9 ||
        !std::isfinite(w.offset)) {
      return "wall '" + w.name + "' needs a finite unit normal with " + std::to_string(dim) +
             " coordinates and a finite offset";
    }
  }
  return "";
}

/// Each joint's initial position, speed bound, target and bounds, and the default speed.
std::string jointsProblem(const SceneTask& task) {
  const Scene& scene = task.scene;
  if (scene.hasRobot() &&
      (!(task.default_joint_velocity > 0.0) || !std::isfinite(task.default_joint_velocity))) {
    return "the default joint velocity must be finite and > 0";
  }
  for (int j = 0; j < scene.numJoints(); ++j) {
    const JointTask& t = task.joints[j];
    const std::string who = "joint '" + scene.robot().joints[j].name + "'";
    const double q0 = scene.initialJoints()(j);
    if (!std::isfinite(q0)) return who + ": the initial position is not finite";
    if (!(t.max_velocity >= 0.0) || !std::isfinite(t.max_velocity)) {
      return who + ": the velocity bound must be finite and >= 0";
    }
    if (!std::isfinite(t.target) || !(t.target_weight >= 0.0) || !std::isfinite(t.target_weight)) {
      return who + ": the target and its weight must be finite (weight >= 0)";
    }
    if (t.has_bounds && (std::isnan(t.lower) || std::isnan(t.upper) || t.lower > t.upper)) {
      return who + ": the bounds are NaN or contradictory (lower > upper)";
    }
    const auto [lower, upper] = jointBounds(task, j);
    if (q0 < lower || q0 > upper) {
      // In the user's radians or lengths (a solve's coordinates are over scene.jointUnit).
      const double unit = scene.jointUnit(j);
      return who + " starts at " + formatNumber(unit * q0) + ", outside its bounds [" +
             formatNumber(unit * lower) + ", " + formatNumber(unit * upper) + "]";
    }
  }
  return "";
}

}  // namespace

SceneTask taskOn(Scene scene) {
  SceneTask task;
  task.bodies.resize(scene.bodies().size());
  task.joints.resize(scene.numJoints());
  task.scene = std::move(scene);
  return task;
}

bool isAllowed(const SceneTask& task, const ContactPair& pair) {
  return task.allowed_pairs.empty() ||
         std::find(task.allowed_pairs.begin(), task.allowed_pairs.end(), pair) !=
             task.allowed_pairs.end();
}

double jointSpeedLimit(const SceneTask& task, int joint) {
  if (task.joints[joint].passive) return 0.0;
  if (task.joints[joint].max_velocity > 0.0) return task.joints[joint].max_velocity;
  const double urdf = task.scene.robot().joints[joint].max_velocity;
  return urdf > 0.0 ? urdf : task.default_joint_velocity;
}

std::pair<double, double> jointBounds(const SceneTask& task, int joint) {
  const JointTask& t = task.joints[joint];
  if (t.has_bounds) return {t.lower, t.upper};
  const KinematicJoint& j = task.scene.robot().joints[joint];
  return {j.lower, j.upper};
}

double targetTolerance(double target_weight) {
  return 1e-3 * std::max(1.0, 100.0 / target_weight);
}

std::string validateTask(const SceneTask& task, const TaskLimits& limits) {
  const Scene& scene = task.scene;
  const int dim = scene.dimension();
  if (dim != 2 && dim != 3) return "the scene must be planar (2) or spatial (3)";
  if (!scene.hasRobot() && scene.bodies().empty()) {
    return "the scene has no bodies (no movable URDF link, none added)";
  }
  if (scene.hasRobot() && static_cast<int>(scene.robot().spheres.size()) > limits.max_spheres) {
    return "too many collision spheres: " + std::to_string(scene.robot().spheres.size()) + " > " +
           std::to_string(limits.max_spheres);
  }
  if (static_cast<int>(scene.bodies().size()) > limits.max_bodies) {
    return "too many bodies: " + std::to_string(scene.bodies().size()) + " > " +
           std::to_string(limits.max_bodies);
  }
  size_t free_spheres = 0;
  for (const SceneBody& body : scene.bodies()) free_spheres += body.spheres.size();
  if (static_cast<int>(free_spheres) > limits.max_spheres) {
    return "too many collision spheres on free bodies: " + std::to_string(free_spheres) + " > " +
           std::to_string(limits.max_spheres);
  }

  if (static_cast<int>(scene.obstacles().size()) > limits.max_obstacles) {
    return "too many obstacles (limit " + std::to_string(limits.max_obstacles) + ")";
  }
  if (static_cast<int>(scene.walls().size()) > limits.max_walls) {
    return "too many walls (limit " + std::to_string(limits.max_walls) + ")";
  }
  for (const FreeLink& free :
       scene.hasRobot() ? scene.robot().free_links : std::vector<FreeLink>{}) {
    const auto stands_for =
        std::find_if(scene.bodies().begin(), scene.bodies().end(),
                     [&](const SceneBody& body) { return body.name == free.link; });
    if (stands_for == scene.bodies().end()) {
      return "link '" + free.link +
             "' is on a planar or floating joint but no free body of the scene stands for it "
             "(robotForScene makes one)";
    }
    // Its answer is the robot's joints, which hold no yaw for it.
    if (stands_for->turns) {
      return "body '" + free.link +
             "' is a free link of the robot's URDF: it translates (add a turning body instead)";
    }
  }
  if (static_cast<int>(task.joints.size()) != scene.numJoints()) {
    return "one joint task per robot coordinate is needed";
  }
  if (task.bodies.size() != scene.bodies().size()) return "one body task per body is needed";
  std::string problem = gridProblem(task.horizon, task.num_intervals, task.control_weight, limits);
  if (problem.empty()) problem = jointsProblem(task);
  if (problem.empty()) problem = bodiesProblem(scene, task.bodies, limits);
  if (!problem.empty()) return problem;
  for (size_t b = 0; b < scene.bodies().size(); ++b) {
    const SceneBody& body = scene.bodies()[b];
    const BodyTask& t = task.bodies[b];
    const std::string who = "body '" + body.name + "'";
    if (scene.hasRobot() && (t.workspace_lower.size() || t.workspace_upper.size())) {
      return who + ": workspace bounds are not supported in robot scenes";
    }
    problem = boundsProblem(t.workspace_lower, t.workspace_upper, dim);
    if (!problem.empty()) return who + ": the workspace bounds " + problem;
    if (!t.insideWorkspace(body.position)) return who + " starts outside its workspace bounds";
  }
  if (scene.controlSize() == 0) return "no body is actuated, so nothing can move";
  problem = fixedGeometryProblem(scene, limits);
  if (problem.empty()) problem = supportProblem(scene);
  if (!problem.empty()) return problem;
  for (int b = 0; b < static_cast<int>(scene.bodies().size()); ++b) {
    // A body that turns about z in a robot's space slides on a table: floating, it may tilt out
    // of the plane the turn is about, which its model does not hold.
    if (scene.bodies()[b].turns && scene.hasRobot() && dim == 3 && scene.supportOf(b) < 0) {
      return "body '" + scene.bodies()[b].name +
             "' turns in a spatial robot scene: it must rest on a level wall (a table) to turn "
             "about its normal";
    }
  }
  const Eigen::VectorXd x0 = scene.initialState();
  const std::vector<ContactPair> all = scene.allPairs();
  for (const ContactPair& pair : all) {
    const double c = scene.constraintValue(pair, x0);
    if (c < -1e-9 * (1.0 + x0.cwiseAbs().maxCoeff())) {
      return scene.pairName(pair) + " overlap at the start";
    }
  }
  for (const ContactPair& allowed : task.allowed_pairs) {
    if (std::find(all.begin(), all.end(), allowed) == all.end())
      return "an allowed contact pair does not exist in the scene";
  }
  return "";
}

std::vector<double> collisionReach(const SceneTask& task) {
  const Scene& scene = task.scene;
  const double travel = task.horizon * controlNorm(task);
  const std::vector<CollisionBody> bodies = scene.collisionBodies();
  std::vector<double> reach(bodies.size(), 0.0);
  const Eigen::VectorXd joint_speeds =
      Eigen::VectorXd::Constant(scene.numJoints(), controlNorm(task));
  // A turning body's sphere at lever arm L: |pdot| <= |v| + (L / rho) |sdot|
  // <= sqrt(1 + L^2 / rho^2) |(v, sdot)|, and a turn moves it by at most 2 L.
  const auto pushed_reach = [&](const CollisionBody& collision) {
    const SceneBody& body = scene.bodies()[collision.free_body];
    if (!body.turns) return travel;
    const double arm = collision.centre.offset.head<2>().norm();
    const double ratio = arm / body.turning_radius;
    return std::min(travel * std::sqrt(1.0 + ratio * ratio), travel + 2.0 * arm);
  };
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].sphere >= 0) {
      reach[i] = sphereReachBound(scene.robot(), bodies[i].sphere, joint_speeds, task.horizon);
    } else if (scene.bodies()[bodies[i].free_body].actuated) {
      reach[i] = travel;
    }
  }
  for (bool grew = true; grew;) {
    grew = false;
    for (const ContactPair& pair : scene.allPairs()) {
      if (pair.kind != ContactPair::Kind::kBody || !isAllowed(task, pair)) continue;
      const bool first_moves = reach[pair.body] > 0.0, second_moves = reach[pair.other] > 0.0;
      if (first_moves == second_moves || separationBound(task, bodies, pair, reach) > 0.0) continue;
      const CollisionBody& still = bodies[first_moves ? pair.other : pair.body];
      if (still.sphere >= 0) continue;  // a robot sphere's reach is its chain's
      for (int sphere : scene.freeBodyCollisionBodies(still.free_body)) {
        reach[sphere] = pushed_reach(bodies[sphere]);
      }
      grew = true;
    }
  }
  return reach;
}

std::string infeasibility(const SceneTask& task) {
  const std::vector<double> reach = collisionReach(task);
  for (size_t b = 0; b < task.bodies.size(); ++b) {
    const BodyTask& t = task.bodies[b];
    const std::string who = "body '" + task.scene.bodies()[b].name + "'";
    // All of a body's collision bodies share its reach.
    const int first = task.scene.freeBodyCollisionBodies(static_cast<int>(b))[0];
    // A yaw is judged in radians with the user's weight (a solve's is over length_unit^2).
    const double unit = task.scene.length_unit;
    const bool turned = std::fabs(t.target_yaw - task.scene.bodies()[b].yaw) >
                        targetTolerance(t.target_yaw_weight * unit * unit);
    if (t.hasYawTarget() && turned && reach[first] == 0.0) {
      return who + " cannot reach its target yaw: nothing that moves can push it";
    }
    if (t.target.size() == 0 || t.target_weight == 0.0) continue;
    if (!t.insideWorkspace(t.target)) return who + " has its target outside its workspace bounds";
    const int support = task.scene.supportOf(static_cast<int>(b));
    if (support >= 0) {  // a spatial scene's body: its height stays
      const double height = task.scene.bodies()[b].position(2);
      if (std::fabs(t.target(2) - height) > targetTolerance(t.target_weight)) {
        return who + " slides on '" + task.scene.walls()[support].name + "' at a height of " +
               formatNumber(task.scene.userLength(height)) +
               ": its target is off that plane (z = " +
               formatNumber(task.scene.userLength(t.target(2))) + ")";
      }
    }
    const Box box = reachableBox(task, static_cast<int>(b), Eigen::Vector3d::Zero(), reach[first]);
    const double miss = boxDistance(box, Box{t.target, t.target});
    // Within its tolerance a target counts as met (a replan from where a push nearly ended).
    if (miss > targetTolerance(t.target_weight)) {
      return who + " cannot reach its target within the horizon: it stays at least " +
             formatNumber(task.scene.userLength(miss)) + " away" +
             (reach[first] > 0.0 ? "" : " (nothing that moves can push it)");
    }
  }
  return "";
}

std::vector<PairDecision> decidePairs(const SceneTask& task) {
  const std::vector<double> reach = collisionReach(task);
  const std::vector<CollisionBody> bodies = task.scene.collisionBodies();
  std::vector<PairDecision> decisions;
  for (const ContactPair& pair : task.scene.allPairs()) {
    if (!isAllowed(task, pair)) {
      decisions.push_back({pair, false, "not among the allowed pairs"});
      continue;
    }
    const bool moves = reach[pair.body] > 0.0 ||
                       (pair.kind == ContactPair::Kind::kBody && reach[pair.other] > 0.0);
    if (!moves) {
      decisions.push_back({pair, false, "neither side can move: nothing can push them"});
      continue;
    }
    const double separation = separationBound(task, bodies, pair, reach);
    if (separation > 0.0) {
      decisions.push_back({pair, false,
                           "cannot touch within the horizon: reachable sets stay " +
                               formatNumber(task.scene.userLength(separation)) + " apart"});
    } else {
      decisions.push_back({pair, true, "can touch within the horizon"});
    }
  }
  return decisions;
}

OcpDefinition buildOcp(const SceneTask& task, const std::vector<ContactPair>& modelled) {
  const Scene& scene = task.scene;
  const int dim = scene.dimension(), nx = scene.stateSize(), nu = scene.controlSize();
  OcpDefinition ocp;
  ocp.model = scene.model(modelled);
  // A held body is pushed only as its support holds it. Its rates may spend half the lift the
  // check allows over the horizon: a bound of 0 would hold weakly active wherever no force acts,
  // as degenerate as the pair with the support it replaces.
  std::vector<int> held;
  for (size_t b = 0; b < task.bodies.size(); ++b) {
    if (task.bodies[b].hold_on_support) held.push_back(static_cast<int>(b));
  }
  const SupportLiftRates lift = scene.supportLiftRates(modelled, held);
  ocp.force_constraints = lift.rates;
  ocp.force_upper.resize(lift.bodies.size());
  for (size_t i = 0; i < lift.bodies.size(); ++i) {
    ocp.force_upper(i) =
        0.5 * kSupportLiftTolerance * boundingRadius(scene.bodies()[lift.bodies[i]]) / task.horizon;
  }
  ocp.initial_state = scene.initialState();
  ocp.horizon = task.horizon;
  ocp.num_intervals = task.num_intervals;
  ocp.control_lower = Eigen::VectorXd::Zero(nu);
  ocp.control_upper = Eigen::VectorXd::Zero(nu);
  ocp.state_lower = Eigen::VectorXd::Constant(nx, -kInf);
  ocp.state_upper = Eigen::VectorXd::Constant(nx, kInf);
  Eigen::VectorXd terminal_weights = Eigen::VectorXd::Zero(nx), targets = ocp.initial_state;
  for (int j = 0; j < scene.numJoints(); ++j) {
    ocp.control_lower(j) = -jointSpeedLimit(task, j);
    ocp.control_upper(j) = jointSpeedLimit(task, j);
    std::tie(ocp.state_lower(j), ocp.state_upper(j)) = jointBounds(task, j);
    if (task.joints[j].target_weight > 0.0) {
      terminal_weights(j) = task.joints[j].target_weight;
      targets(j) = task.joints[j].target;
    }
  }
  for (int b = 0; b < static_cast<int>(scene.bodies().size()); ++b) {
    const BodyTask& t = task.bodies[b];
    const int first = scene.stateIndex(b);
    if (scene.bodies()[b].actuated) {
      ocp.control_lower.segment(scene.controlIndex(b), dim).setConstant(-t.max_speed);
      ocp.control_upper.segment(scene.controlIndex(b), dim).setConstant(t.max_speed);
    }
    if (t.workspace_lower.size()) ocp.state_lower.segment(first, dim) = t.workspace_lower;
    if (t.workspace_upper.size()) ocp.state_upper.segment(first, dim) = t.workspace_upper;
    if (t.hasTarget()) {
      terminal_weights.segment(first, dim).setConstant(t.target_weight);
      targets.segment(first, dim) = t.target;
    }
    if (t.hasYawTarget()) {  // in s = rho yaw: w (yaw - target)^2 = (w / rho^2) (s - rho target)^2
      const double rho = scene.turningRadius(b);
      terminal_weights(first + dim) = t.target_yaw_weight / (rho * rho);
      targets(first + dim) = rho * t.target_yaw;
    }
  }
  ocp.state_lower = ocp.state_lower.cwiseMax(-kInf);  // infinite bounds as Ipopt's infinity
  ocp.state_upper = ocp.state_upper.cwiseMin(kInf);
  if (nu > 0 && task.control_weight > 0.0) {
    Eigen::VectorXd weights = Eigen::VectorXd::Zero(nx + nu);
    weights.tail(nu).setConstant(task.control_weight);
    // A revolute joint's speed as the speed of an arc at the robot's reach (the projection's
    // metric, Scene::model): the cost in lengths throughout.
    const double reach = scene.hasRobot() ? robotReach(scene.robot()) : 1.0;
    for (int j = 0; j < scene.numJoints(); ++j) {
      if (scene.robot().joints[j].type != JointType::kPrismatic) {
        weights(nx + j) *= reach * reach;
      }
    }
    ocp.lagrange_cost =
        QuadraticFunction::weightedDistance(weights, Eigen::VectorXd::Zero(nx + nu));
  }
  if ((terminal_weights.array() != 0.0).any()) {
    ocp.mayer_cost = QuadraticFunction::weightedDistance(terminal_weights, targets);
  }
  return ocp;
}

}  // namespace fesd
