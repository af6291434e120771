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
/// revolute joints' targets) by factor^2; angles, the horizon and the intervals unchanged. Its
/// optimum is the task's scaled by `factor`, its objective factor^2 times.
SceneTask scaledTask(const SceneTask& task, double factor);

/// The task a solve in units of `length_scale` solves: scaledTask by 1 / length_scale with every
/// robot coordinate a length in those units too (inLengthUnits: q / length_scale, its targets,
/// bounds and speeds with it, target weights unchanged), so that its state and controls are the
/// task's divided by length_scale and its objective the task's by length_scale^2; its scene's
/// length_unit records what one unit stands for.
SceneTask taskInLengthUnits(const SceneTask& task, double length_scale);

}  // namespace fesd
