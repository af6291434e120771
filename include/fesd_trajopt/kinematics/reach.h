#pragma once

#include <Eigen/Dense>

#include "fesd_trajopt/kinematics/kinematic_model.h"

namespace fesd {

/// An upper bound on |p_s(q) - o_j(q)| over every q within the limits, for a joint j on the
/// sphere's chain (0 off it): the lengths of the fixed offsets from joint j down the chain to the
/// centre, plus the largest travel of each prismatic joint below j.
double leverArmBound(const KinematicModel& model, int sphere, int joint);

/// An upper bound on how far a sphere centre can move within `horizon` when each coordinate j
/// moves no faster than velocities(j): sum_j velocities(j) horizon times the lever-arm bound
/// (revolute and continuous) or 1 (prismatic), times the joint's coordinate_scale. The robot's
/// own motion only; a push adds to it.
double sphereReachBound(const KinematicModel& model, int sphere, const Eigen::VectorXd& velocities,
                        double horizon);

/// The robot's reach: the most a sphere can move per unit of a revolute coordinate (the longest
/// lever arm of any revolute joint to a sphere it moves, times its coordinate_scale); 1 when no
/// revolute joint moves a sphere. Scenes weigh a revolute joint's motion by it (a radian counts
/// as an arc at the reach, design.md), which makes a robot's physics independent of its units.
double robotReach(const KinematicModel& model);

}  // namespace fesd
