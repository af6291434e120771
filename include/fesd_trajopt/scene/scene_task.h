#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/model/ocp_definition.h"
#include "fesd_trajopt/scene/disc_scene.h"

namespace fesd {

/// What a body should do in a scene task (parallel to DiscScene::bodies()).
struct BodyTask {
  double max_speed = 10.0;     ///< actuated: |u_d| <= max_speed in each coordinate
  Eigen::VectorXd target;      ///< empty: no target
  double target_weight = 0.0;  ///< weight of |p(T) - target|^2 in the cost
  Eigen::VectorXd workspace_lower, workspace_upper;  ///< per coordinate; empty: none
};

/// A trajectory-optimisation task on a disc scene: drive the bodies to their targets with the
/// actuated ones, min  control_weight int |u|^2 dt + sum_b w_b |p_b(T) - target_b|^2.
struct SceneTask {
  DiscScene scene{2};
  std::vector<BodyTask> bodies;
  double horizon = 5.0;
  int num_intervals = 40;
  double control_weight = 1e-4;
  /// Contact pairs that may be modelled; empty means every pair of the scene.
  std::vector<ContactPair> allowed_pairs;
};

/// How near a body must end to its target for the target to count as met: 1e-3 for target
/// weights >= 100, 1e-3 * 100 / weight below (the optimum of a soft target trades its distance
/// against the control effort, more so the lighter its weight).
double targetTolerance(double target_weight);

/// Limits on the size of a task (requests beyond them are refused).
struct TaskLimits {
  int max_bodies = 30;
  int max_spheres = 200;  ///< a robot's collision spheres (they are not bodies)
  int max_obstacles = 50;
  int max_walls = 20;
  int max_intervals = 200;
  int max_elements = 6;
  int max_stages = 4;
  double max_horizon = 1e4;
  double max_coordinate = 1e6;
  /// An NLP whose solve is estimated to need more memory (estimatedSolverMib) is refused.
  double max_solver_mib = 2048.0;
};

// Checks shared by every kind of scene task (discs, robots); each returns "" or a message
// naming the problem.
/// The horizon, the number of control intervals and the control weight.
std::string gridProblem(double horizon, int num_intervals, double control_weight,
                        const TaskLimits& limits);
/// Each body (one task per body): a unique name, radius, initial position, speed bound, target
/// and weight. Workspace bounds are the caller's.
std::string bodiesProblem(const DiscScene& scene, const std::vector<BodyTask>& bodies,
                          const TaskLimits& limits);
/// Every obstacle's radius and position, every wall's unit normal and offset.
std::string fixedGeometryProblem(const DiscScene& scene, const TaskLimits& limits);

/// Checks a task for what it must not contain: non-finite numbers, radii <= 0, wrong
/// dimensions, no actuated body, bodies overlapping each other, an obstacle or a wall at the start,
/// bounds that exclude the start, sizes beyond the limits. Returns "" or a message naming the
/// problem.
std::string validateTask(const SceneTask& task, const TaskLimits& limits);

/// Checks a valid task (validateTask) for goals it cannot meet: a target outside the body's
/// workspace bounds, or beyond the reach of everything that could move it within the horizon
/// (the conservative reach of decidePairs; a passive body nothing can push has none). Returns ""
/// or a message naming the body and the target.
std::string infeasibility(const SceneTask& task);

/// Whether a contact pair is modelled, and why (or why not).
struct PairDecision {
  ContactPair pair;
  bool modelled;  ///< a constraint of the NLP (decidePairs: it can touch within the horizon)
  std::string reason;
  /// In reach but not modelled: checked on the solution instead (lazy pairs, solveSceneTask).
  bool checked = false;
  /// The smallest gap between the pair's surfaces along the answer: a modelled pair's at the
  /// stage points (where the plan holds c >= 0; between them its collocation polynomial may dip
  /// by the interpolation error), a checked pair's along the sampled polynomials (densePath).
  /// NaN for the others and before a solve.
  double min_distance = std::numeric_limits<double>::quiet_NaN();
};

/// Simulate only the effects the scene calls for: a pair is modelled when it is allowed and
/// can touch within the horizon. Conservative reachability: the DCS velocity is the projection
/// of f onto the tangent cone, which does not lengthen it, so no body moves farther than
/// D = T |u_max| (the norm over all actuated coordinates at their bounds). Actuated bodies have
/// reach D; a passive body has reach D if it can touch a body with reach (through an allowed
/// pair; repeated until nothing changes), else 0, like obstacles and walls. A pair can touch
/// if the boxes start +- reach (clipped to the workspace bounds) come within the radii.
std::vector<PairDecision> decidePairs(const SceneTask& task);

/// The OCP of a task with the given modelled pairs as its constraints.
OcpDefinition buildOcp(const SceneTask& task, const std::vector<ContactPair>& modelled);

}  // namespace fesd
