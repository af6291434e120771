#pragma once

#include <string>

#include "fesd_trajopt/kinematics/kinematic_model.h"

namespace fesd {

/// The first moving joint (in the model's order) that can take a sphere below it out of its
/// (x, y) plane: a revolute axis not parallel to z or a prismatic axis not in the plane, both in
/// the world at q = 0. Empty when there is none; then every sphere keeps its z at every q, since
/// the joints above only turn about z and slide in the plane.
std::string firstJointLeavingPlane(const KinematicModel& model);

/// Planar in (x, y): no joint leaves the plane.
inline bool isPlanar(const KinematicModel& model) {
  return firstJointLeavingPlane(model).empty();
}

}  // namespace fesd
