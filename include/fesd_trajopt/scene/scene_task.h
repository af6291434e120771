#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/model/ocp_definition.h"
#include "fesd_trajopt/scene/scene.h"

namespace fesd {

/// What a free body should do in a scene task (parallel to Scene::bodies()).
struct BodyTask {
  double max_speed = 10.0;     ///< actuated: |u_d| <= max_speed in each coordinate
  Eigen::VectorXd target;      ///< empty: no target
  double target_weight = 0.0;  ///< weight of |p(T) - target|^2 in the cost
  Eigen::VectorXd workspace_lower, workspace_upper;  ///< per coordinate; empty: none
  /// A turning body's: weight of (yaw(T) - target_yaw)^2 in the cost (yaw continuous from its
  /// start: the target is met as given, not modulo 2 pi).
  double target_yaw = 0.0;
  double target_yaw_weight = 0.0;
  /// On a support: the plan pushes the body only as its support holds it (the pairs' lift rates
  /// within kSupportLiftTolerance, Scene::supportLiftRates). solveSceneTask sets it from the
  /// round after one whose plan would have lifted the body.
  bool hold_on_support = false;

  /// A target the cost weighs.
  bool hasTarget() const { return target.size() && target_weight > 0.0; }
  bool hasYawTarget() const { return target_yaw_weight > 0.0; }
  /// p within the workspace bounds (every coordinate; no bounds: everywhere).
  bool insideWorkspace(const Eigen::VectorXd& p) const {
    return !(workspace_lower.size() && (p.array() < workspace_lower.array()).any()) &&
           !(workspace_upper.size() && (p.array() > workspace_upper.array()).any());
  }
};

/// What a joint of the scene's robot should do (parallel to the robot's coordinates).
struct JointTask {
  /// Moves only when pushed, like a door's hinge: no command (its speed bound is 0), only the
  /// contacts' projection turns it.
  bool passive = false;
  double max_velocity = 0.0;  ///< |u_j| bound; 0: the URDF's, or SceneTask's default
  double target = 0.0;
  double target_weight = 0.0;  ///< weight of (q_j(T) - target)^2 in the cost
  /// Position bounds overriding the URDF's (state bounds at every stage point).
  bool has_bounds = false;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
};

/// A trajectory-optimisation task on a scene: drive the bodies and joints to their targets with
/// the actuated ones, min  control_weight int |u|^2 dt + sum_b w_b |p_b(T) - target_b|^2
/// + sum_b w_yaw,b (yaw_b(T) - target_yaw_b)^2 + sum_j w_j (q_j(T) - target_j)^2, a revolute
/// joint's speed in |u|^2 as an arc's at the robot's reach (robotReach: times reach^2).
struct SceneTask {
  Scene scene{2};
  std::vector<BodyTask> bodies;   ///< one per free body
  std::vector<JointTask> joints;  ///< one per robot coordinate (none without a robot)
  double horizon = 5.0;
  int num_intervals = 40;
  double control_weight = 1e-4;
  double default_joint_velocity = 1.0;  ///< for joints whose URDF gives no velocity limit
  /// Contact pairs that may be modelled; empty means every pair of the scene.
  std::vector<ContactPair> allowed_pairs;
};

/// A task on the scene with a default BodyTask per free body and JointTask per robot coordinate.
SceneTask taskOn(Scene scene);

/// Whether the task allows a pair to be modelled (its allowed_pairs is empty or holds it).
bool isAllowed(const SceneTask& task, const ContactPair& pair);
/// A joint's speed bound: 0 for a passive joint, else the task's, else the URDF's, else the
/// task's default.
double jointSpeedLimit(const SceneTask& task, int joint);
/// A joint's position bounds: the task's override, else the URDF's (+-infinity if none).
std::pair<double, double> jointBounds(const SceneTask& task, int joint);

/// How near a body must end to its target for the target to count as met: 1e-3 for target
/// weights >= 100, 1e-3 * 100 / weight below (the optimum of a soft target trades its distance
/// against the control effort, more so the lighter its weight).
double targetTolerance(double target_weight);

/// Limits on the size of a task (requests beyond them are refused).
struct TaskLimits {
  int max_bodies = 30;
  int max_spheres = 200;  ///< a robot's collision spheres, and those of the free bodies
  int max_obstacles = 50;
  int max_walls = 20;
  int max_intervals = 200;
  int max_elements = 6;
  int max_stages = 4;
  double max_horizon = 1e4;
  double max_coordinate = 1e6;  ///< in units of the length scale a solve sees the task in
  /// An NLP whose solve is estimated to need more memory (estimatedSolverMib) is refused.
  double max_solver_mib = 2048.0;
};

/// Checks a task for what it must not contain: non-finite numbers, radii <= 0, wrong
/// dimensions, nothing actuated, pairs overlapping at the start, bounds that exclude the start,
/// sizes beyond the limits (limits.max_spheres for a robot), a free link of the robot that no free
/// body stands for (robotForScene makes them) or one that turns, a turning body in a spatial
/// robot scene, workspace bounds in a robot scene. Returns "" or a message naming the problem.
std::string validateTask(const SceneTask& task, const TaskLimits& limits);

/// Checks a valid task (validateTask) for goals it cannot meet: a target outside the body's
/// workspace bounds, or beyond the reach of everything that could move it within the horizon
/// (the conservative reach of decidePairs; a passive body nothing can push has none), or a target
/// yaw of a body nothing can push. Returns "" or a message naming the body and the target.
std::string infeasibility(const SceneTask& task);

/// Whether a contact pair is modelled, and why (or why not).
struct PairDecision {
  ContactPair pair;
  bool modelled;  ///< a constraint of the NLP (decidePairs: it can touch within the horizon)
  std::string reason;
  /// In reach but not modelled: checked on the solution instead (lazy pairs).
  bool checked = false;
  /// The smallest gap between the pair's surfaces along the answer: a modelled pair's at the
  /// stage points (where the plan holds c >= 0; between them its collocation polynomial may dip
  /// by the interpolation error), a checked pair's along the sampled polynomials (densePath).
  /// NaN for the others and before a solve.
  double min_distance = std::numeric_limits<double>::quiet_NaN();
};

/// How far each collision body can get from its start within the horizon. The projected
/// velocity is no longer than the commanded one (the projection does not expand), so
/// |xdot| <= |u_max| over every control coordinate at its bound: an actuated free body, or a
/// pushed one, moves at most T |u_max|; a robot sphere at most sphereReachBound with every joint
/// at |u_max| (a push can speed one joint up, never the whole). A passive body gets its reach once
/// it can touch something that moves (through an allowed pair; repeated until nothing changes),
/// with all its spheres; else 0, like obstacles and walls.
std::vector<double> collisionReach(const SceneTask& task);

/// Simulate only the effects the scene calls for: a pair is modelled when it is allowed and
/// can touch within the horizon (collisionReach). Two free bodies can touch if the boxes
/// start +- reach (clipped to the workspace bounds) come within the radii; a robot sphere if its
/// start gap is at most both reaches.
std::vector<PairDecision> decidePairs(const SceneTask& task);

/// The OCP of a task with the given modelled pairs as its constraints: the joints' and actuated
/// bodies' speeds as control bounds, joint limits and workspaces as state bounds.
OcpDefinition buildOcp(const SceneTask& task, const std::vector<ContactPair>& modelled);

}  // namespace fesd
