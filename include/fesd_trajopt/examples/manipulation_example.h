#pragma once

#include <Eigen/Dense>

#include "fesd_trajopt/model/ocp_definition.h"
#include "fesd_trajopt/planning/push_plan.h"
#include "fesd_trajopt/scene/scene.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// Pozharskiy et al. 2024, Sec. IV-B: two actuated discs (R = 1) push a passive disc (R = 2) to a
/// goal. x = (p1, p2, p3), u = (u1, u2), f = (u1, u2, 0, 0), c_j = |p3 - pj|^2 - (R3 + Rj)^2, j =
/// 1, 2; x0 = (-10, 10, 5, -5, 0, 0), -10 <= u <= 10, p1_x <= -2.5, p2_x >= 2.5 (neither actuator
/// can do the job alone); cost int u^T R u dt + (x(T) - x_T)^T Q_T (x(T) - x_T), R = 1e-4 I, Q_T =
/// diag(1, 1, 1, 1, 1e3, 1e3), x_T = (-10, 0, 10, 0, 0, 10), T = 5.
namespace manipulation_example {

/// The scene, targets, weights, speed and workspace bounds as a task.
SceneTask task(int num_intervals);
/// The same task with the object's goal elsewhere (replanning examples).
SceneTask task(int num_intervals, const Eigen::Vector2d& object_goal);
/// The two contact pairs of the paper: actuated disc j against the passive disc. Reachability
/// pruning (decidePairs) finds the same: the workspace bounds keep the actuators apart.
std::vector<ContactPair> contactPairs();
OcpDefinition ocp(int num_intervals);
/// The push plan of the task (planPushes): the first guess the showcase is solved from.
PushPlan plan(int num_intervals);
Eigen::VectorXd targetState();
Eigen::Vector2d objectGoal();  ///< (0, 10)

}  // namespace manipulation_example
}  // namespace fesd
