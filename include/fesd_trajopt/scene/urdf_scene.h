#pragma once

#include <string>
#include <vector>

#include "fesd_trajopt/scene/scene.h"

namespace fesd {

/// A scene read from URDF, or the reason it could not be.
struct UrdfScene {
  Scene scene{2};
  std::vector<std::string> ignored_links;  ///< links without usable collision geometry
  std::string error;                       ///< empty on success
};

/// What a URDF may hold: it comes with a request, so it is bounded before it is walked.
struct UrdfLimits {
  size_t max_bytes = 8u << 20;
  size_t max_links = 2000;
};

/// Builds a disc scene from URDF collision geometry at the zero configuration:
///  - a link with a collision sphere, or (planar scenes) a cylinder whose axis is normal to the
///    plane, is a disc/sphere of that radius at the collision frame's origin;
///  - links attached to the root through fixed joints only are fixed obstacles, all other links
///    movable bodies (passive until configured otherwise);
///  - planar scenes use (x, y), spatial ones (x, y, z).
/// Links without such geometry are listed in ignored_links. Malformed XML gives an error; a URDF
/// without movable links is fine (a request may add every body); one beyond `limits` is refused.
UrdfScene sceneFromUrdf(const std::string& xml, bool planar, const UrdfLimits& limits = {});

}  // namespace fesd
