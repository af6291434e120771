#include "fesd_trajopt/scene/urdf_scene.h"

#include <functional>

#include <urdf_parser/urdf_parser.h>
#include <Eigen/Geometry>

namespace fesd {
namespace {

Eigen::Isometry3d toIsometry(const urdf::Pose& pose) {
  Eigen::Isometry3d t = Eigen::Isometry3d::Identity();
  t.translation() << pose.position.x, pose.position.y, pose.position.z;
  t.linear() =
      Eigen::Quaterniond(pose.rotation.w, pose.rotation.x, pose.rotation.y, pose.rotation.z)
          .normalized()
          .toRotationMatrix();
  return t;
}

}  // namespace

UrdfScene sceneFromUrdf(const std::string& xml, bool planar) {
  UrdfScene result;
  result.scene = DiscScene(planar ? 2 : 3);
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
  const int dim = planar ? 2 : 3;
  std::function<void(const urdf::LinkConstSharedPtr&, const Eigen::Isometry3d&, bool)> visit =
      [&](const urdf::LinkConstSharedPtr& link, const Eigen::Isometry3d& pose, bool fixed) {
        const urdf::CollisionSharedPtr collision = link->collision;
        bool used = false;
        if (collision && collision->geometry) {
          const Eigen::Isometry3d frame = pose * toIsometry(collision->origin);
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
            if (fixed) {
              result.scene.obstacles().push_back({link->name, radius, position});
            } else {
              result.scene.bodies().push_back({link->name, radius, position, false});
            }
            used = true;
          }
        }
        if (!used && link != model->getRoot()) result.ignored_links.push_back(link->name);
        for (const urdf::JointSharedPtr& joint : link->child_joints) {
          const urdf::LinkConstSharedPtr child = model->getLink(joint->child_link_name);
          if (!child) continue;
          visit(child, pose * toIsometry(joint->parent_to_joint_origin_transform),
                fixed && joint->type == urdf::Joint::FIXED);
        }
      };
  visit(model->getRoot(), Eigen::Isometry3d::Identity(), true);
  return result;
}

}  // namespace fesd
