#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

#include "fesd_trajopt/scene/scene.h"

namespace fesd {

/// A URDF planar joint (about the scene's z, hanging from the world) whose link is a body of the
/// scene: what maps the body's position and yaw back to the joint's coordinates.
struct UrdfPlanarJoint {
  std::string joint;
  int body = -1;             ///< its link's body in UrdfScene::scene
  Eigen::Isometry3d origin;  ///< the joint's frame in the world
  double turn_sign = 1.0;    ///< -1 when the joint's axis points down: theta turns against yaw
  /// The body's position less the link's origin at yaw 0, world-aligned (the centre of pressure
  /// of a turning body, the mean of its spheres otherwise).
  Eigen::VectorXd centre;
};

/// The joint's coordinates (x, y, theta) when its body is at `position` with `yaw` (0 for a body
/// that does not turn): the link's displacement in the joint's frame and its turn.
Eigen::Vector3d planarJointValues(const UrdfPlanarJoint& joint, const Eigen::VectorXd& position,
                                  double yaw);

/// A scene read from URDF, or the reason it could not be.
struct UrdfScene {
  Scene scene{2};
  std::vector<UrdfPlanarJoint> planar_joints;
  std::vector<std::string> ignored_links;   ///< links without usable collision geometry
  std::vector<std::string> ignored_shapes;  ///< other shapes of links with spheres
  std::string error;                        ///< empty on success
};

/// What a URDF may hold: it comes with a request, so it is bounded before it is walked.
struct UrdfLimits {
  size_t max_bytes = 8u << 20;
  size_t max_links = 2000;
};

/// Builds a scene of discs or spheres from URDF collision geometry at the zero configuration:
///  - a link's collision spheres, and (planar scenes) cylinders whose axis is normal to the
///    plane, are its spheres: links attached to the root through fixed joints only are fixed
///    obstacles (one per sphere, "<link>/sphere_<k>" when several), all other links movable
///    bodies (passive until configured otherwise), one per link: a sphere at its centre, or
///    several spheres moving together about their mean;
///  - a link of several spheres on a planar joint about z from a link fixed to the world turns
///    (SceneBody::turns, at its centre of pressure; theta about the joint frame's z, as MoveIt
///    reads a planar joint): its joint is listed in planar_joints, as is any planar joint about z
///    of the world carrying a body; links with spheres below a turning link are refused (they
///    would not turn with it);
///  - planar scenes use (x, y), spatial ones (x, y, z).
/// Links without such geometry are listed in ignored_links. Malformed XML gives an error; a URDF
/// without movable links is fine (a request may add every body); one beyond `limits` is refused.
UrdfScene sceneFromUrdf(const std::string& xml, bool planar, const UrdfLimits& limits = {});

}  // namespace fesd
