#include "fesd_trajopt/scene/urdf_scene.h"

#include <vector>

#include <urdf_parser/urdf_parser.h>
#include <Eigen/Geometry>

#include "fesd_trajopt/kinematics/urdf_pose.h"

namespace fesd {

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
  };
  // An explicit stack, children pushed last-first: the depth-first order of the links without a
  // recursion as deep as the URDF's chain.
  std::vector<Visit> stack{{model->getRoot(), Eigen::Isometry3d::Identity(), true}};
  while (!stack.empty()) {
    const Visit visit = stack.back();
    stack.pop_back();
    const urdf::LinkConstSharedPtr& link = visit.link;
    const urdf::CollisionSharedPtr collision = link->collision;
    bool used = false;
    if (collision && collision->geometry) {
      const Eigen::Isometry3d frame = visit.pose * isometryFromUrdf(collision->origin);
      double radius = 0.0;
      if (collision->geometry->type == urdf::Geometry::SPHERE) {
        radius = static_cast<const urdf::Sphere&>(*collision->geometry).radius;
      } else if (planar && collision->geometry->type == urdf::Geometry::CYLINDER) {
        const Eigen::Vector3d axis = frame.linear().col(2);
        if (std::abs(axis.z()) > 1.0 - 1e-6) {
          radius = static_cast<const urdf::Cylinder&>(*collision->geometry).radius;
        }
      }
      if (radius != 0.0) {
        const Eigen::VectorXd position = frame.translation().head(dim);
        if (visit.fixed) {
          result.scene.obstacles().push_back({link->name, radius, position});
        } else {
          result.scene.bodies().push_back({link->name, radius, position, false});
        }
        used = true;
      }
    }
    if (!used && link != model->getRoot()) result.ignored_links.push_back(link->name);
    for (auto joint = link->child_joints.rbegin(); joint != link->child_joints.rend(); ++joint) {
      const urdf::LinkConstSharedPtr child = model->getLink((*joint)->child_link_name);
      if (!child) continue;
      stack.push_back({child,
                       visit.pose * isometryFromUrdf((*joint)->parent_to_joint_origin_transform),
                       visit.fixed && (*joint)->type == urdf::Joint::FIXED});
    }
  }
  return result;
}

}  // namespace fesd
