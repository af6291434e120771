#include "fesd_trajopt/scene/robot_task.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fesd_trajopt/function/quadratic_function.h"
#include "fesd_trajopt/kinematics/reach.h"
#include "fesd_trajopt/nlp/nlp_assembly.h"

namespace fesd {
namespace {

constexpr double kInf = NlpAssembly::kInfinity;

std::string formatNumber(double value) {
  std::ostringstream out;
  out.precision(3);
  out << value;
  return out.str();
}

/// |u_max| over every control coordinate at its bound.
double controlNorm(const RobotTask& task) {
  double squared = 0.0;
  for (int j = 0; j < task.scene.numJoints(); ++j) {
    squared += jointSpeedLimit(task, j) * jointSpeedLimit(task, j);
  }
  const DiscScene& discs = task.scene.discs();
  for (size_t b = 0; b < discs.bodies().size(); ++b) {
    if (discs.bodies()[b].actuated) {
      squared += discs.dimension() * task.bodies[b].max_speed * task.bodies[b].max_speed;
    }
  }
  return std::sqrt(squared);
}

/// A lower bound on the gap between the pair's surfaces during the task.
double separationBound(const RobotTask& task, const RobotPair& pair,
                       const std::vector<double>& reach) {
  const RobotScene& scene = task.scene;
  if (pair.kind == RobotPair::Kind::kWall)
    return scene.pairGap(pair, scene.initialState()) - reach[pair.body];
  const double other_reach = pair.kind == RobotPair::Kind::kBody ? reach[pair.other] : 0.0;
  return scene.pairGap(pair, scene.initialState()) - reach[pair.body] - other_reach;
}

}  // namespace

double jointSpeedLimit(const RobotTask& task, int joint) {
  if (task.joints[joint].passive) return 0.0;
  if (task.joints[joint].max_velocity > 0.0) return task.joints[joint].max_velocity;
  const double urdf = task.scene.robot().joints[joint].max_velocity;
  return urdf > 0.0 ? urdf : task.default_joint_velocity;
}

std::pair<double, double> jointBounds(const RobotTask& task, int joint) {
  const JointTask& t = task.joints[joint];
  if (t.has_bounds) return {t.lower, t.upper};
  const KinematicJoint& j = task.scene.robot().joints[joint];
  return {j.lower, j.upper};
}

std::string validateRobotTask(const RobotTask& task, const TaskLimits& limits) {
  const RobotScene& scene = task.scene;
  const DiscScene& discs = scene.discs();
  const int dim = scene.dimension();
  if (dim != 2 && dim != 3) return "the scene must be planar (2) or spatial (3)";
  if (static_cast<int>(scene.robot().spheres.size()) > limits.max_spheres) {
    return "too many collision spheres: " + std::to_string(scene.robot().spheres.size()) + " > " +
           std::to_string(limits.max_spheres);
  }
  if (static_cast<int>(discs.bodies().size()) > limits.max_bodies) {
    return "too many bodies (limit " + std::to_string(limits.max_bodies) + ")";
  }
  if (static_cast<int>(discs.obstacles().size()) > limits.max_obstacles) {
    return "too many obstacles (limit " + std::to_string(limits.max_obstacles) + ")";
  }
  if (static_cast<int>(discs.walls().size()) > limits.max_walls) {
    return "too many walls (limit " + std::to_string(limits.max_walls) + ")";
  }
  for (const FreeLink& free : scene.robot().free_links) {
    if (std::none_of(discs.bodies().begin(), discs.bodies().end(),
                     [&](const SceneBody& body) { return body.name == free.link; })) {
      return "link '" + free.link +
             "' is on a planar or floating joint but no free body of the scene stands for it "
             "(robotForScene makes one)";
    }
  }
  if (static_cast<int>(task.joints.size()) != scene.numJoints()) {
    return "one joint task per robot coordinate is needed";
  }
  if (task.bodies.size() != discs.bodies().size()) return "one body task per body is needed";
  std::string problem = gridProblem(task.horizon, task.num_intervals, task.control_weight, limits);
  if (!problem.empty()) return problem;
  if (!(task.default_joint_velocity > 0.0) || !std::isfinite(task.default_joint_velocity)) {
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
      return who + " starts at " + formatNumber(q0) + ", outside its bounds [" +
             formatNumber(lower) + ", " + formatNumber(upper) + "]";
    }
  }
  problem = bodiesProblem(discs, task.bodies, limits);
  if (problem.empty()) problem = fixedGeometryProblem(discs, limits);
  if (!problem.empty()) return problem;
  for (size_t b = 0; b < discs.bodies().size(); ++b) {
    const BodyTask& t = task.bodies[b];
    if (t.workspace_lower.size() || t.workspace_upper.size()) {
      return "body '" + discs.bodies()[b].name +
             "': workspace bounds are not supported in robot scenes";
    }
  }
  const Eigen::VectorXd x0 = scene.initialState();
  for (const RobotPair& pair : scene.allPairs()) {
    if (scene.pairGap(pair, x0) < -1e-9) return scene.pairName(pair) + " overlap at the start";
  }
  return "";
}

bool isAllowed(const RobotTask& task, const RobotPair& pair) {
  return task.allowed_pairs.empty() ||
         std::find(task.allowed_pairs.begin(), task.allowed_pairs.end(), pair) !=
             task.allowed_pairs.end();
}

std::vector<double> collisionReach(const RobotTask& task) {
  const RobotScene& scene = task.scene;
  const double travel = task.horizon * controlNorm(task);
  const std::vector<CollisionBody>& bodies = scene.collisionBodies();
  std::vector<double> reach(bodies.size(), 0.0);
  const Eigen::VectorXd joint_speeds =
      Eigen::VectorXd::Constant(scene.numJoints(), controlNorm(task));
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].sphere >= 0) {
      reach[i] = sphereReachBound(scene.robot(), bodies[i].sphere, joint_speeds, task.horizon);
    } else if (scene.discs().bodies()[bodies[i].free_body].actuated) {
      reach[i] = travel;
    }
  }
  const Eigen::VectorXd x0 = scene.initialState();
  for (bool grew = true; grew;) {
    grew = false;
    for (const RobotPair& pair : scene.allPairs()) {
      if (pair.kind != RobotPair::Kind::kBody || !isAllowed(task, pair)) continue;
      for (const auto& [mover, still] :
           {std::make_pair(pair.body, pair.other), std::make_pair(pair.other, pair.body)}) {
        if (reach[mover] == 0.0 || reach[still] > 0.0 || bodies[still].sphere >= 0) continue;
        if (scene.pairGap(pair, x0) - reach[mover] > 0.0) continue;
        // A free body moves with all its spheres.
        for (int sphere : scene.freeBodyCollisionBodies(bodies[still].free_body)) {
          reach[sphere] = travel;
        }
        grew = true;
      }
    }
  }
  return reach;
}

std::vector<RobotPairDecision> decideRobotPairs(const RobotTask& task) {
  const std::vector<double> reach = collisionReach(task);
  std::vector<RobotPairDecision> decisions;
  for (const RobotPair& pair : task.scene.allPairs()) {
    if (!isAllowed(task, pair)) {
      decisions.push_back({pair, false, "not among the allowed pairs"});
      continue;
    }
    const bool moves =
        reach[pair.body] > 0.0 || (pair.kind == RobotPair::Kind::kBody && reach[pair.other] > 0.0);
    if (!moves) {
      decisions.push_back({pair, false, "neither side can move"});
      continue;
    }
    const double separation = separationBound(task, pair, reach);
    if (separation > 0.0) {
      decisions.push_back({pair, false,
                           "cannot touch within the horizon: reachable sets stay " +
                               formatNumber(separation) + " apart"});
    } else {
      decisions.push_back({pair, true, "can touch within the horizon"});
    }
  }
  return decisions;
}

OcpDefinition buildRobotOcp(const RobotTask& task, const std::vector<RobotPair>& modelled) {
  const RobotScene& scene = task.scene;
  const DiscScene& discs = scene.discs();
  const int dim = scene.dimension(), nx = scene.stateSize(), nu = scene.controlSize();
  const int nq = scene.numJoints();
  OcpDefinition ocp;
  ocp.model = scene.model(modelled);
  ocp.initial_state = scene.initialState();
  ocp.horizon = task.horizon;
  ocp.num_intervals = task.num_intervals;
  ocp.control_lower = Eigen::VectorXd::Zero(nu);
  ocp.control_upper = Eigen::VectorXd::Zero(nu);
  ocp.state_lower = Eigen::VectorXd::Constant(nx, -kInf);
  ocp.state_upper = Eigen::VectorXd::Constant(nx, kInf);
  Eigen::VectorXd terminal_weights = Eigen::VectorXd::Zero(nx), targets = ocp.initial_state;
  for (int j = 0; j < nq; ++j) {
    ocp.control_lower(j) = -jointSpeedLimit(task, j);
    ocp.control_upper(j) = jointSpeedLimit(task, j);
    const auto [lower, upper] = jointBounds(task, j);
    ocp.state_lower(j) = std::max(lower, -kInf);
    ocp.state_upper(j) = std::min(upper, kInf);
    if (task.joints[j].target_weight > 0.0) {
      terminal_weights(j) = task.joints[j].target_weight;
      targets(j) = task.joints[j].target;
    }
  }
  for (int b = 0; b < static_cast<int>(discs.bodies().size()); ++b) {
    const BodyTask& t = task.bodies[b];
    if (discs.bodies()[b].actuated) {
      const int first = nq + discs.controlIndex(b);
      ocp.control_lower.segment(first, dim).setConstant(-t.max_speed);
      ocp.control_upper.segment(first, dim).setConstant(t.max_speed);
    }
    if (t.target.size() && t.target_weight > 0.0) {
      terminal_weights.segment(scene.bodyStateIndex(b), dim).setConstant(t.target_weight);
      targets.segment(scene.bodyStateIndex(b), dim) = t.target;
    }
  }
  if (task.control_weight > 0.0) {
    Eigen::VectorXd weights = Eigen::VectorXd::Zero(nx + nu);
    weights.tail(nu).setConstant(task.control_weight);
    ocp.lagrange_cost =
        QuadraticFunction::weightedDistance(weights, Eigen::VectorXd::Zero(nx + nu));
  }
  if ((terminal_weights.array() != 0.0).any()) {
    ocp.mayer_cost = QuadraticFunction::weightedDistance(terminal_weights, targets);
  }
  return ocp;
}

}  // namespace fesd
