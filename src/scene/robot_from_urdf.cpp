#include "fesd_trajopt/scene/robot_from_urdf.h"

#include <algorithm>
#include <cmath>

#include "fesd_trajopt/kinematics/planarity.h"

namespace fesd {
namespace {

/// A free link as a passive free body (RobotForScene::free_bodies), or why it cannot be one.
std::string freeLinkBody(const KinematicModel& robot, const FreeLink& free, int dimension,
                         SceneBody& body) {
  const std::string who = "free link '" + free.link + "' (joint '" + free.joint + "')";
  const int parent = robot.linkIndex(free.parent_link);
  if (parent < 0 || robot.links[parent].joint >= 0) {
    return who + " hangs from a moving link: only free links of the world are modelled";
  }
  if (free.planar && dimension != 2) {
    return who + " is planar in a spatial scene: its plane is not modelled";
  }
  // The parent is fixed to the world, so the frame it hangs from is the world's.
  if (free.planar &&
      std::abs(std::abs((free.pose.linear() * free.axis).normalized().z()) - 1.0) > 1e-9) {
    return who + " slides in a plane other than the scene's (x, y): its normal must be z";
  }
  if (free.has_children) return who + " has links below it: a free link is modelled as one body";
  if (free.spheres.empty()) {
    return who + " has no collision sphere" +
           (dimension == 2 ? " (or cylinder normal to the plane)" : "") +
           ": a free link needs one to be a body";
  }
  // The body's position is the mean of its spheres' centres (its only sphere's centre).
  std::vector<Eigen::VectorXd> centres;
  Eigen::VectorXd mean = Eigen::VectorXd::Zero(dimension);
  for (const KinematicSphere& sphere : free.spheres) {
    centres.push_back(sphere.joint_centre.head(dimension));
    mean += centres.back() / static_cast<double>(free.spheres.size());
  }
  body = {free.link, 0.0, mean, false};
  for (size_t s = 0; s < free.spheres.size(); ++s) {
    const Eigen::VectorXd offset = centres[s] - mean;
    body.radius = std::max(body.radius, offset.norm() + free.spheres[s].radius);
    if (free.spheres.size() == 1) break;  // the body itself is its sphere
    Eigen::Vector3d padded = Eigen::Vector3d::Zero();
    padded.head(dimension) = offset;
    body.spheres.push_back({free.spheres[s].name, padded, free.spheres[s].radius});
  }
  return "";
}

std::string freeLinkBodies(const KinematicModel& robot, int dimension, RobotForScene& result) {
  for (const FreeLink& free : robot.free_links) {
    SceneBody body;
    const std::string error = freeLinkBody(robot, free, dimension, body);
    if (!error.empty()) return error;
    result.free_bodies.push_back(body);
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
    result.error = freeLinkBodies(*result.robot, 3, result);
    return result;
  }
  options.planar = true;  // read again: cylinders normal to the plane become discs
  KinematicModelResult flat = buildKinematicModel(urdf_xml, options);
  if (!flat.error.empty()) {
    result.error = flat.error;
    return result;
  }
  result.robot = std::make_shared<const KinematicModel>(std::move(flat.model));
  result.error = freeLinkBodies(*result.robot, 2, result);
  return result;
}

}  // namespace fesd
