#pragma once

#include "fesd_trajopt/kinematics/kinematic_model.h"

namespace fesd {

/// The same robot in other length units: every length multiplied by `factor` (joint origins, link
/// offsets, sphere centres and radii, free links' poses, prismatic joints' limits and
/// velocities); angles and revolute joints unchanged.
KinematicModel withLengthsScaled(const KinematicModel& model, double factor);

/// The robot as a solve in units of `length_scale` sees it: lengths divided by it and every
/// coordinate a length in those units, q~ = q / length_scale (a revolute joint turns
/// length_scale radians per unit of its coordinate; its limits and velocity divided with it).
/// The Euclidean projection in (q~, p / length_scale) is the original's in (q, p): the same
/// physics, every number scaled alike.
KinematicModel inLengthUnits(const KinematicModel& model, double length_scale);

}  // namespace fesd
