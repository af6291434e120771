#pragma once

#include <memory>
#include <string>
#include <vector>

#include "fesd_trajopt/kinematics/kinematic_model.h"
#include "fesd_trajopt/scene/scene.h"

namespace fesd {

/// Whether a robot scene is planar: inferred from the robot, or forced either way.
enum class PlanarChoice { kInferred, kPlanar, kSpatial };

/// A robot read for a scene, with the scene's dimension, or why not (error non-empty).
struct RobotForScene {
  std::shared_ptr<const KinematicModel> robot;
  int dimension = 3;
  /// The robot's free links (planar or floating joints) as passive free bodies at their URDF
  /// poses, named after their links: at the mean of their spheres' centres, of the radius that
  /// bounds them, carrying their spheres when they are several.
  std::vector<SceneBody> free_bodies;
  std::string error;
};

/// Reads a robot (buildKinematicModel) and decides its scene's dimension: planar (2) iff every
/// joint keeps the spheres in the (x, y) plane (isPlanar) unless forced. Forcing planar on a robot
/// that leaves the plane is refused, naming the first joint that does (firstJointLeavingPlane).
/// Planar models also take cylinders normal to the plane as discs. A free link becomes a free
/// body of the scene (a puck in the robot's URDF) when a body can stand for it: it hangs from a
/// link fixed to the world, carries collision spheres (cylinders normal to the plane in planar
/// scenes; several translate together without rotating) and no links below it, and a planar
/// joint only in a planar scene; any other is refused by name.
RobotForScene robotForScene(const std::string& urdf_xml, PlanarChoice choice,
                            const KinematicModelOptions& limits = {});

}  // namespace fesd
