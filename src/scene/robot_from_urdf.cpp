#include "fesd_trajopt/scene/robot_from_urdf.h"

#include <algorithm>
#include <cmath>

#include <urdf_parser/urdf_parser.h>

#include "fesd_trajopt/kinematics/planarity.h"
#include "fesd_trajopt/kinematics/urdf_pose.h"
#include "fesd_trajopt/scene/urdf_scene.h"

namespace fesd {
namespace {

/// The free links of `robot` as bodies (RobotForScene::free_bodies), or why one cannot be.
std::string freeLinkBodies(const std::string& urdf_xml, const KinematicModel& robot, int dimension,
                           std::vector<SceneBody>& bodies) {
  if (robot.free_links.empty()) return "";
  // Parsed before by buildKinematicModel, within its limits: these reads cannot fail.
  const urdf::ModelInterfaceSharedPtr urdf = urdf::parseURDF(urdf_xml);
  const UrdfScene scene = sceneFromUrdf(urdf_xml, dimension == 2);
  for (const FreeLink& free : robot.free_links) {
    const std::string who = "free link '" + free.link + "' (joint '" + free.joint + "')";
    const int parent = robot.linkIndex(free.parent_link);
    if (parent < 0 || robot.links[parent].joint >= 0) {
      return who + " hangs from a moving link: only free links of the world are modelled";
    }
    if (free.planar && dimension != 2) {
      return who + " is planar in a spatial scene: its plane is not modelled";
    }
    const urdf::JointConstSharedPtr joint = urdf->getJoint(free.joint);
    if (free.planar) {
      const Eigen::Vector3d normal =
          (robot.links[parent].offset * isometryFromUrdf(joint->parent_to_joint_origin_transform))
              .linear() *
          Eigen::Vector3d(joint->axis.x, joint->axis.y, joint->axis.z);
      if (std::abs(std::abs(normal.normalized().z()) - 1.0) > 1e-9) {
        return who + " slides in a plane other than the scene's (x, y): its normal must be z";
      }
    }
    const urdf::LinkConstSharedPtr link = urdf->getLink(free.link);
    if (!link->child_links.empty()) {
      return who + " has links below it: a free link is modelled as one body";
    }
    const auto body = std::find_if(scene.scene.bodies().begin(), scene.scene.bodies().end(),
                                   [&](const SceneBody& b) { return b.name == free.link; });
    if (link->collision_array.size() != 1 || body == scene.scene.bodies().end()) {
      return who + " must carry exactly one collision sphere" +
             (dimension == 2 ? " (or cylinder normal to the plane)" : "") + ", it has " +
             std::to_string(link->collision_array.size()) + " collision element(s)" +
             (body == scene.scene.bodies().end() && link->collision_array.size() == 1
                  ? " of another shape"
                  : "");
    }
    bodies.push_back(*body);
  }
  return "";
}

}  // namespace

RobotForScene robotForScene(const std::string& urdf_xml, PlanarChoice choice,
                            const KinematicModelOptions& limits) {
  RobotForScene result;
  KinematicModelOptions options = limits;
  options.planar = false;
  KinematicModelResult spatial = buildKinematicModel(urdf_xml, options);
  if (!spatial.error.empty()) {
    result.error = spatial.error;
    return result;
  }
  const std::string leaving = firstJointLeavingPlane(spatial.model);
  if (choice == PlanarChoice::kPlanar && !leaving.empty()) {
    result.error = "the scene cannot be planar: joint '" + leaving +
                   "' moves the robot out of the (x, y) plane";
    return result;
  }
  const bool planar =
      choice == PlanarChoice::kPlanar || (choice == PlanarChoice::kInferred && leaving.empty());
  result.dimension = planar ? 2 : 3;
  if (!planar) {
    result.robot = std::make_shared<const KinematicModel>(std::move(spatial.model));
    result.error = freeLinkBodies(urdf_xml, *result.robot, 3, result.free_bodies);
    return result;
  }
  options.planar = true;  // read again: cylinders normal to the plane become discs
  KinematicModelResult flat = buildKinematicModel(urdf_xml, options);
  if (!flat.error.empty()) {
    result.error = flat.error;
    return result;
  }
  result.robot = std::make_shared<const KinematicModel>(std::move(flat.model));
  result.error = freeLinkBodies(urdf_xml, *result.robot, 2, result.free_bodies);
  return result;
}

}  // namespace fesd
