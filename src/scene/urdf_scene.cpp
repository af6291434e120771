#include "fesd_trajopt/scene/urdf_scene.h"

#include <cmath>
#include <vector>

#include <urdf_parser/urdf_parser.h>

#include "fesd_trajopt/kinematics/urdf_pose.h"

namespace fesd {
namespace {

struct LinkSphere {
  Eigen::VectorXd centre;
  double radius;
};

/// The link's collision spheres (and, in planar scenes, cylinders normal to the plane) at `pose`;
/// its other collision shapes into `ignored` ("<link>/collision_<k>").
std::vector<LinkSphere> linkSpheres(const urdf::Link& link, const Eigen::Isometry3d& pose, int dim,
                                    std::vector<std::string>& ignored) {
  std::vector<urdf::CollisionSharedPtr> collisions = link.collision_array;
  if (collisions.empty() && link.collision) collisions.push_back(link.collision);
  std::vector<LinkSphere> spheres;
  for (size_t k = 0; k < collisions.size(); ++k) {
    const urdf::CollisionSharedPtr& collision = collisions[k];
    if (!collision || !collision->geometry) continue;
    const Eigen::Isometry3d frame = pose * isometryFromUrdf(collision->origin);
    double radius = 0.0;
    if (collision->geometry->type == urdf::Geometry::SPHERE) {
      radius = static_cast<const urdf::Sphere&>(*collision->geometry).radius;
    } else if (dim == 2 && collision->geometry->type == urdf::Geometry::CYLINDER &&
               std::abs(frame.linear().col(2).z()) > 1.0 - 1e-6) {
      radius = static_cast<const urdf::Cylinder&>(*collision->geometry).radius;
    }
    if (radius != 0.0) {
      spheres.push_back({frame.translation().head(dim), radius});
    } else {
      ignored.push_back(link.name + "/collision_" + std::to_string(k));
    }
  }
  return spheres;
}

std::string sphereName(const std::string& link, size_t k, size_t count) {
  return count == 1 ? link : link + "/sphere_" + std::to_string(k);
}

/// One body of a moving link's spheres: the sphere itself, or the spheres about their mean.
SceneBody linkBody(const std::string& link, const std::vector<LinkSphere>& spheres, int dim) {
  SceneBody body{link, spheres[0].radius, spheres[0].centre, false};
  if (spheres.size() == 1) return body;
  body.position = Eigen::VectorXd::Zero(dim);
  for (const LinkSphere& sphere : spheres) body.position += sphere.centre / spheres.size();
  for (size_t k = 0; k < spheres.size(); ++k) {
    Eigen::Vector3d offset = Eigen::Vector3d::Zero();
    offset.head(dim) = spheres[k].centre - body.position;
    body.spheres.push_back({sphereName(link, k, spheres.size()), offset, spheres[k].radius});
  }
  body.radius = boundingRadius(body);
  return body;
}

/// The planar joint's turn sign: +-1 when it moves its link in the scene's (x, y) plane (its axis
/// along its frame's z, that z along the world's up or down), theta turning about its frame's z
/// as MoveIt reads a planar joint; 0 otherwise.
double planarTurnSign(const urdf::Joint& joint, const Eigen::Isometry3d& origin) {
  if (joint.type != urdf::Joint::PLANAR) return 0.0;
  const Eigen::Vector3d axis =
      Eigen::Vector3d(joint.axis.x, joint.axis.y, joint.axis.z).normalized();
  const double up = origin.linear()(2, 2);
  if (!(std::abs(std::abs(axis.z()) - 1.0) <= 1e-9) || !(std::abs(std::abs(up) - 1.0) <= 1e-9)) {
    return 0.0;
  }
  return up > 0.0 ? 1.0 : -1.0;
}

}  // namespace

Eigen::Vector3d planarJointValues(const UrdfPlanarJoint& joint, const Eigen::VectorXd& position,
                                  double yaw) {
  const int dim = static_cast<int>(position.size());
  Eigen::Vector3d link = Eigen::Vector3d::Zero();
  link.head(dim) = position - joint.centre;
  link.head<2>() += joint.centre.head<2>() - Eigen::Rotation2Dd(yaw) * joint.centre.head<2>();
  if (dim == 2) link.z() = joint.origin.translation().z();
  const Eigen::Vector3d local = joint.origin.inverse() * link;
  return {local.x(), local.y(), joint.turn_sign * yaw};
}

UrdfScene sceneFromUrdf(const std::string& xml, bool planar, const UrdfLimits& limits) {
  UrdfScene result;
  result.scene = Scene(planar ? 2 : 3);
  if (xml.size() > limits.max_bytes) {
    result.error = "URDF too large: " + std::to_string(xml.size()) + " bytes > " +
                   std::to_string(limits.max_bytes);
    return result;
  }
  urdf::ModelInterfaceSharedPtr model;
  try {
    model = urdf::parseURDF(xml);
  } catch (const std::exception& error) {
    result.error = std::string("malformed URDF: ") + error.what();
    return result;
  }
  if (!model || !model->getRoot()) {
    result.error =
        "malformed URDF: it could not be parsed (see the node's log for the parser's "
        "message)";
    return result;
  }
  if (model->links_.size() > limits.max_links) {
    result.error = "URDF with too many links: " + std::to_string(model->links_.size()) + " > " +
                   std::to_string(limits.max_links);
    return result;
  }
  const int dim = planar ? 2 : 3;
  struct Visit {
    urdf::LinkConstSharedPtr link;
    Eigen::Isometry3d pose;
    bool fixed;
    double turn_sign;           ///< of its joint when planar about z from a fixed link, else 0
    std::string turning_above;  ///< a link above it that turns, or ""
  };
  // An explicit stack, children pushed last-first: the depth-first order of the links without a
  // recursion as deep as the URDF's chain.
  std::vector<Visit> stack{{model->getRoot(), Eigen::Isometry3d::Identity(), true, 0.0, ""}};
  while (!stack.empty()) {
    const Visit visit = stack.back();
    stack.pop_back();
    const urdf::LinkConstSharedPtr& link = visit.link;
    std::vector<std::string> ignored;
    const std::vector<LinkSphere> spheres = linkSpheres(*link, visit.pose, dim, ignored);
    if (spheres.empty() && link != model->getRoot()) {
      result.ignored_links.push_back(link->name);
    } else {
      result.ignored_shapes.insert(result.ignored_shapes.end(), ignored.begin(), ignored.end());
    }
    if (!spheres.empty() && !visit.turning_above.empty()) {
      result.error = "link '" + link->name + "' hangs from '" + visit.turning_above +
                     "', which turns on its planar joint: its spheres would not turn with it (give "
                     "them to '" +
                     visit.turning_above + "')";
      return result;
    }
    const bool turns = visit.turn_sign != 0.0 && spheres.size() > 1;
    if (!spheres.empty() && visit.fixed) {
      for (size_t k = 0; k < spheres.size(); ++k) {
        result.scene.obstacles().push_back(
            {sphereName(link->name, k, spheres.size()), spheres[k].radius, spheres[k].centre});
      }
    } else if (!spheres.empty()) {
      SceneBody body = linkBody(link->name, spheres, dim);
      if (turns) turnAboutPressureCentre(body);
      if (visit.turn_sign != 0.0) {
        result.planar_joints.push_back(
            {link->parent_joint->name, static_cast<int>(result.scene.bodies().size()), visit.pose,
             visit.turn_sign, body.position - visit.pose.translation().head(dim)});
      }
      result.scene.bodies().push_back(std::move(body));
    }
    for (auto joint = link->child_joints.rbegin(); joint != link->child_joints.rend(); ++joint) {
      const urdf::LinkConstSharedPtr child = model->getLink((*joint)->child_link_name);
      if (!child) continue;
      const Eigen::Isometry3d pose =
          visit.pose * isometryFromUrdf((*joint)->parent_to_joint_origin_transform);
      stack.push_back({child, pose, visit.fixed && (*joint)->type == urdf::Joint::FIXED,
                       visit.fixed ? planarTurnSign(**joint, pose) : 0.0,
                       turns ? link->name : visit.turning_above});
    }
  }
  return result;
}

}  // namespace fesd
