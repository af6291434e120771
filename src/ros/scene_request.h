#pragma once

#include <string>
#include <vector>

#include <fesd_trajopt/BodySpec.h>
#include <fesd_trajopt/ContactPair.h>
#include <fesd_trajopt/Obstacle.h>
#include <fesd_trajopt/Wall.h>
#include <ros/node_handle.h>

#include "fesd_trajopt/scene/scene_task.h"
#include "fesd_trajopt/scene/urdf_scene.h"
#include "node_config.h"
#include "robot_request.h"

namespace fesd_ros {

/// The scene part that SolveTrajectory and Simulate requests share.
struct SceneFields {
  std::string urdf, urdf_param;
  bool planar_override = false, planar = true;
  std::vector<fesd_trajopt::BodySpec> bodies;
  std::vector<fesd_trajopt::Obstacle> obstacles;
  std::vector<fesd_trajopt::Wall> walls;
  std::vector<fesd_trajopt::ContactPair> allowed_pairs;
};

template <class Request>
SceneFields sceneFields(const Request& request) {
  return {request.urdf,        request.urdf_param,   request.planar_override != 0,
          request.planar != 0, request.bodies,       request.obstacles,
          request.walls,       request.allowed_pairs};
}

/// A task built from the configuration, the URDF and a request's scene fields.
struct TaskBuild {
  fesd::SceneTask task;
  std::string error;                                 ///< non-empty: the request is invalid, and why
  std::vector<std::string> notes;                    ///< e.g. URDF links that were ignored
  std::vector<fesd::UrdfPlanarJoint> planar_joints;  ///< a scene URDF's, answered as joints
};

/// The configured defaults, the request's scene source and overrides: the scene task (horizon
/// and intervals from the configuration; the caller applies the request's). A URDF with moving
/// joints is a robot (robotForScene, its free links free bodies) among the request's bodies,
/// obstacles and walls; any other a scene of discs or spheres (sceneFromUrdf).
TaskBuild buildTask(const NodeConfig& config, const SceneFields& request, const RobotFields& robot,
                    const ros::NodeHandle& node);

/// The request's scene URDF (its urdf, else the parameter urdf_param, else ~scene_urdf) into
/// `xml`; returns "" or why there is none.
std::string urdfSource(const NodeConfig& config, const SceneFields& request,
                       const ros::NodeHandle& node, std::string& xml);

/// The configured bodies' settings and the request's bodies, obstacles and walls applied to
/// task.scene (horizon and intervals from the configuration); returns "" or why not.
std::string applySceneFields(const NodeConfig& config, const SceneFields& request,
                             fesd::SceneTask& task);

}  // namespace fesd_ros
