#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/model/ocp_definition.h"
#include "fesd_trajopt/scene/robot_scene.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// What a joint of the robot should do (parallel to the robot's coordinates).
struct JointTask {
  /// Moves only when pushed, like a door's hinge: no command (its speed bound is 0), only the
  /// contacts' projection turns it.
  bool passive = false;
  double max_velocity = 0.0;  ///< |u_j| bound; 0: the URDF's, or RobotTask's default
  double target = 0.0;
  double target_weight = 0.0;  ///< weight of (q_j(T) - target)^2 in the cost
  /// Position bounds overriding the URDF's (state bounds at every stage point).
  bool has_bounds = false;
  double lower = -std::numeric_limits<double>::infinity();
  double upper = std::numeric_limits<double>::infinity();
};

/// A trajectory-optimisation task on a robot scene, as SceneTask on a disc scene:
/// min control_weight int |u|^2 dt + sum_j w_j (q_j(T) - target_j)^2 + sum_b w_b |p_b(T) - t_b|^2.
struct RobotTask {
  /// A task on the scene with one default JointTask per coordinate and BodyTask per free body.
  explicit RobotTask(RobotScene robot_scene)
      : scene(std::move(robot_scene)),
        joints(scene.numJoints()),
        bodies(scene.discs().bodies().size()) {}

  RobotScene scene;
  std::vector<JointTask> joints;  ///< one per robot coordinate
  std::vector<BodyTask> bodies;   ///< one per free body of scene.discs()
  double horizon = 5.0;
  int num_intervals = 40;
  double control_weight = 1e-4;
  double default_joint_velocity = 1.0;  ///< for joints whose URDF gives no velocity limit
  /// Pairs that may be modelled (RobotScene::allPairs' entries); empty means every pair.
  std::vector<RobotPair> allowed_pairs;
};

/// Whether the task allows a pair to be modelled (its allowed_pairs is empty or holds it).
bool isAllowed(const RobotTask& task, const RobotPair& pair);

/// A joint's speed bound: 0 for a passive joint, else the task's, else the URDF's, else the
/// task's default.
double jointSpeedLimit(const RobotTask& task, int joint);
/// A joint's position bounds: the task's override, else the URDF's (+-infinity if none).
std::pair<double, double> jointBounds(const RobotTask& task, int joint);

/// Checks a robot task as validateTask does a disc task (non-finite numbers, sizes beyond the
/// limits including limits.max_spheres, joints starting outside their bounds, bodies' radii,
/// pairs overlapping at the start; a free link of the robot that no free body of the scene
/// stands for, see robotForScene). Returns "" or a message naming the problem.
std::string validateRobotTask(const RobotTask& task, const TaskLimits& limits);

/// Whether a pair is modelled, and why (or why not).
struct RobotPairDecision {
  RobotPair pair;
  bool modelled;
  std::string reason;
  /// In reach but not modelled: checked on the solution instead (lazy pairs, solveRobotTask).
  bool checked = false;
  /// The smallest gap along the answer (solveRobotTask): a modelled pair's at the stage points
  /// (where the plan holds it), a checked pair's between them too (densePath); NaN when not
  /// measured.
  double min_distance = std::numeric_limits<double>::quiet_NaN();
};

/// How far each collision body can get from its start within the horizon. The projected velocity
/// is no longer than the commanded one in x = (q, p), so |xdot| <= |u_max| (over every coordinate
/// at its bound): a free actuated body or a pushed one moves at most T |u_max|, a robot sphere
/// at most sphereReachBound with every joint at |u_max| (a push can speed one joint up, never
/// the whole). A passive body gets its reach once it can touch something that moves through an
/// allowed pair.
std::vector<double> collisionReach(const RobotTask& task);

/// The allowed pairs that can touch within the horizon (their start gap minus both reaches <= 0).
std::vector<RobotPairDecision> decideRobotPairs(const RobotTask& task);

/// The OCP of a robot task with the given modelled pairs: joint speeds and the actuated bodies'
/// speeds as control bounds, joint position limits and workspaces as state bounds.
OcpDefinition buildRobotOcp(const RobotTask& task, const std::vector<RobotPair>& modelled);

}  // namespace fesd
