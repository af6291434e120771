#pragma once

#include <string>

#include "fesd_trajopt/kinematics/kinematic_model.h"

namespace fesd_test {

/// The text of a file shipped in config/robots (empty if it cannot be read).
std::string readRobotFile(const std::string& name);

/// A small robot with every kind of coordinate: a revolute joint with an unnormalised tilted
/// axis, a branch, a prismatic joint, a rotated fixed joint and a continuous joint without
/// limits; a box collision besides the spheres.
std::string mixedJointsUrdf();

/// The kinematic model of a shipped URDF; fails the calling test if it cannot be built.
fesd::KinematicModel loadShippedRobot(const std::string& name);

}  // namespace fesd_test
