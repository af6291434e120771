#pragma once

#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// The length a task is solved in (docs/design.md, "One plan in any units"): the median radius
/// of the collision bodies its controls move (the actuated free bodies' spheres, the robot's
/// spheres on a joint), else of all free bodies' spheres; 1 without any. It depends on sizes
/// only, not on positions, targets or bounds, so that a replan of the same bodies keeps it.
double lengthScale(const SceneTask& task);

/// The same task in other length units: every length multiplied by `factor` (radii, positions,
/// sphere offsets, turning radii, walls' offsets, targets, workspace and speed bounds, a robot's
/// links and prismatic joints: withLengthsScaled) and the weights of angles (target yaws,
/// revolute joints' targets) by factor^2; angles, the horizon, the intervals and the default joint
/// velocity unchanged. Its optimum is the task's scaled by `factor`, its objective factor^2 times.
SceneTask scaledTask(const SceneTask& task, double factor);

/// The task a solve in units of `length_scale` solves: scaledTask by 1 / length_scale with every
/// robot coordinate a length in those units too (inLengthUnits: a revolute joint's the arc at
/// the robot's reach; its targets, bounds and speeds with it, its target weight such that the
/// cost is the same), so that its objective is the task's over length_scale^2 and its state and
/// controls the task's over their SolveUnits; its scene's length_unit records what one unit
/// stands for.
SceneTask taskInLengthUnits(const SceneTask& task, double length_scale);

/// How a task's numbers relate to those of the task its solve sees: each the solve's times its
/// unit.
struct SolveUnits {
  double length = 1.0;    ///< the length scale
  Eigen::VectorXd state;  ///< per state coordinate: length, or a revolute joint's radians per unit
  Eigen::VectorXd control;  ///< per control: its coordinate's
};

/// The units of the scene a solve sees (of taskInLengthUnits; a user's scene: all 1).
SolveUnits solveUnits(const Scene& solve_scene);

}  // namespace fesd
