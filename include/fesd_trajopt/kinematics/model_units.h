#pragma once

#include "fesd_trajopt/kinematics/kinematic_model.h"

namespace fesd {

/// The same robot in other length units: every length multiplied by `factor` (joint origins, link
/// offsets, sphere centres and radii, free links' poses, prismatic joints' limits and
/// velocities); angles and revolute joints unchanged.
KinematicModel withLengthsScaled(const KinematicModel& model, double factor);

/// The robot as a solve in units of `length_scale` sees it: lengths divided by it and every
/// coordinate a length in those units: a prismatic joint's q / length_scale, a revolute joint's
/// the arc it sweeps at the robot's reach (robotReach), q reach / length_scale (it turns
/// length_scale / reach radians per unit of its coordinate; limits and velocity with it). Its
/// reach is 1: a scene's projection, which weighs a revolute joint by reach^2, is then the
/// Euclidean one in these coordinates, and the same for the robot in any units.
KinematicModel inLengthUnits(const KinematicModel& model, double length_scale);

}  // namespace fesd
