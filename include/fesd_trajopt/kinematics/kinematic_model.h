#pragma once

#include <string>
#include <vector>

#include <Eigen/Geometry>

namespace fesd {

/// The joints that are a robot's coordinates q (angle in radians, displacement in metres).
enum class JointType { kRevolute, kContinuous, kPrismatic };

/// One coordinate of the robot. Joints are ordered parent before child, so a chain from the root
/// lists increasing indices.
struct KinematicJoint {
  std::string name;
  JointType type;
  Eigen::Vector3d axis;  ///< unit axis in the joint's frame
  /// The joint's frame at q_j = 0 in its parent joint's moved frame (the world for parent -1);
  /// fixed joints in between are folded in.
  Eigen::Isometry3d origin;
  int parent;              ///< the nearest moving joint above, -1 at the root
  std::vector<int> chain;  ///< the moving joints from the root down to this one, inclusive
  double lower, upper;     ///< position limits; +-infinity for continuous joints
  double max_velocity;     ///< the URDF's velocity limit; 0 when it gives none
  /// The joint's motion per unit of its coordinate: radians (revolute) or model lengths
  /// (prismatic). 1 as read from a URDF; a model in a solve's units (model_units.h) turns a
  /// revolute joint by L radians per unit, so that every coordinate is a length in units of L.
  double coordinate_scale = 1.0;
};

/// A link of the kinematic tree: rigidly attached to the moved frame of a joint (or the world).
struct KinematicLink {
  std::string name;
  int joint;                 ///< the nearest moving joint above, -1 when fixed to the world
  Eigen::Isometry3d offset;  ///< the link's frame in that joint's moved frame
};

/// A collision sphere: `<link>/sphere_<k>`, k the index among that link's `<collision>` elements.
struct KinematicSphere {
  std::string name;
  int link;                      ///< -1 for a free link's sphere
  Eigen::Vector3d local_centre;  ///< in the link's frame
  /// In the moved frame of the link's joint (or the world); a free link's: in the frame its
  /// parent link hangs from (FreeLink::pose's).
  Eigen::Vector3d joint_centre;
  double radius;
};

/// A link on a planar or floating joint: not a coordinate of the robot but a free body of the
/// scene; the builder does not descend below it.
struct FreeLink {
  std::string link, joint, parent_link;
  bool planar;  ///< planar joint, else floating
  /// The link's frame at its URDF pose, in the frame its parent link hangs from (the world for a
  /// parent fixed to it).
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
  Eigen::Vector3d axis = Eigen::Vector3d::UnitZ();  ///< the joint's (a planar joint's normal)
  bool has_children = false;                        ///< links hang below it
  std::vector<KinematicSphere> spheres;             ///< its collision spheres, as a robot link's
};

/// A robot read once from its URDF; evaluated per q by the free functions of
/// forward_kinematics.h.
struct KinematicModel {
  std::string root_link;
  std::vector<KinematicJoint> joints;
  std::vector<KinematicLink> links;
  std::vector<KinematicSphere> spheres;
  std::vector<FreeLink> free_links;
  std::vector<std::string> ignored_shapes;  ///< "<link>/collision_<k> (<shape>)" not modelled

  int numCoordinates() const { return static_cast<int>(joints.size()); }
  /// The moving joints that move a sphere, root first (empty for a sphere fixed to the world).
  const std::vector<int>& chainOf(int sphere) const;
  /// Index of the joint, link or sphere of that name, -1 if there is none.
  int jointIndex(const std::string& name) const;
  int linkIndex(const std::string& name) const;
  int sphereIndex(const std::string& name) const;
};

/// What a URDF may hold before it is refused (the input is a request's, so it is bounded).
struct KinematicModelOptions {
  /// Planar scenes also take cylinders whose axis is normal to the (x, y) plane (at q = 0) as
  /// discs of the cylinder's radius.
  bool planar = false;
  int max_links = 1000;
  int max_coordinates = 64;
  int max_spheres = 2000;
};

/// A model read from URDF, or the reason it could not be (error non-empty).
struct KinematicModelResult {
  KinematicModel model;
  std::string error;
};

/// Reads the kinematic tree (iteratively: the URDF's depth decides no recursion): revolute,
/// continuous and prismatic joints become coordinates with normalised axes (a zero axis is
/// refused), fixed joints attach, planar and floating joints end in free links; every
/// `<collision>` sphere becomes a sphere, other shapes are listed in ignored_shapes.
KinematicModelResult buildKinematicModel(const std::string& urdf_xml,
                                         const KinematicModelOptions& options = {});

}  // namespace fesd
