#pragma once

#include <memory>
#include <string>

#include "fesd_trajopt/kinematics/kinematic_model.h"

namespace fesd {

/// Whether a robot scene is planar: inferred from the robot, or forced either way.
enum class PlanarChoice { kInferred, kPlanar, kSpatial };

/// A robot read for a scene, with the scene's dimension, or why not (error non-empty).
struct RobotForScene {
  std::shared_ptr<const KinematicModel> robot;
  int dimension = 3;
  std::string error;
};

/// Reads a robot (buildKinematicModel) and decides its scene's dimension: planar (2) iff every
/// joint keeps the spheres in the (x, y) plane (isPlanar) unless forced. Forcing planar on a robot
/// that leaves the plane is refused, naming the first joint that does (firstJointLeavingPlane).
/// Planar models also take cylinders normal to the plane as discs.
RobotForScene robotForScene(const std::string& urdf_xml, PlanarChoice choice,
                            const KinematicModelOptions& limits = {});

}  // namespace fesd
