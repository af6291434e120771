#include "scene_request.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <set>

#include "fesd_trajopt/scene/urdf_scene.h"
#include "robot_request.h"

namespace fesd_ros {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

Eigen::VectorXd coordinates(const geometry_msgs::Point& p, int dim) {
  Eigen::VectorXd v(dim);
  v(0) = p.x;
  v(1) = p.y;
  if (dim == 3) v(2) = p.z;
  return v;
}

/// Workspace bounds from the configuration's x_min/x_max/... map.
void configuredWorkspace(const BodyConfig& config, int dim, fesd::BodyTask& task) {
  task.workspace_lower = Eigen::VectorXd::Constant(dim, -kInf);
  task.workspace_upper = Eigen::VectorXd::Constant(dim, kInf);
  const char axes[] = {'x', 'y', 'z'};
  for (int d = 0; d < dim; ++d) {
    const auto lower = config.workspace.find(std::string(1, axes[d]) + "_min");
    const auto upper = config.workspace.find(std::string(1, axes[d]) + "_max");
    if (lower != config.workspace.end()) task.workspace_lower(d) = lower->second;
    if (upper != config.workspace.end()) task.workspace_upper(d) = upper->second;
  }
}

/// Bounds given in a request: empty keeps the configured ones; otherwise one per coordinate.
std::string requestedBounds(const std::vector<double>& values, int dim, Eigen::VectorXd& bounds) {
  if (values.empty()) return "";
  if (static_cast<int>(values.size()) != dim) {
    return "needs " + std::to_string(dim) + " values, got " + std::to_string(values.size());
  }
  for (double v : values) {
    if (std::isnan(v)) return "contains NaN";
  }
  bounds = Eigen::Map<const Eigen::VectorXd>(values.data(), dim);
  return "";
}

/// An added body's spheres from the request (offsets in its frame, radii), its bounding radius.
std::string requestedSpheres(const fesd_trajopt::BodySpec& spec, const fesd::TaskLimits& limits,
                             fesd::SceneBody& body) {
  if (spec.sphere_offsets.size() != spec.sphere_radii.size()) {
    return " has " + std::to_string(spec.sphere_offsets.size()) + " sphere offsets and " +
           std::to_string(spec.sphere_radii.size()) + " radii (one radius per sphere)";
  }
  if (spec.sphere_offsets.empty()) return "";
  if (!spec.add) return " is a link of the URDF: its spheres come from there";
  if (static_cast<int>(spec.sphere_offsets.size()) > limits.max_spheres) {
    return " has " + std::to_string(spec.sphere_offsets.size()) + " spheres (limit " +
           std::to_string(limits.max_spheres) + ")";
  }
  body.spheres.clear();
  body.radius = 0.0;
  for (size_t k = 0; k < spec.sphere_offsets.size(); ++k) {
    const geometry_msgs::Point& o = spec.sphere_offsets[k];
    const Eigen::Vector3d offset(o.x, o.y, o.z);
    const double radius = spec.sphere_radii[k];
    if (!offset.allFinite() || !(radius > 0.0) || radius > limits.max_coordinate ||
        offset.norm() > limits.max_coordinate) {
      return " has sphere " + std::to_string(k) +
             " with a non-finite or too large offset or radius, or a radius that is not > 0";
    }
    if (body.position.size() == 2 && offset.z() != 0.0) {
      return " has sphere " + std::to_string(k) + " off the plane (z offset in a planar scene)";
    }
    body.spheres.push_back({spec.name + "/sphere_" + std::to_string(k), offset, radius});
  }
  if (body.spheres.size() == 1) {  // one sphere: the body itself, at its position
    body.radius = body.spheres[0].radius;
    body.spheres.clear();
  }
  return "";
}

/// A body's spheres and turning from the request: "" or why not (starting with a space).
/// BodySpec.support: "" leaves the body on the level wall it rests on (SupportMode::kAuto),
/// "none" lets it float, a wall's name puts it on that wall (validateTask checks it rests there).
std::string applySupport(const fesd_trajopt::BodySpec& spec, fesd::Scene& scene) {
  if (spec.support.empty()) return "";
  const auto body = std::find_if(scene.bodies().begin(), scene.bodies().end(),
                                 [&](const fesd::SceneBody& b) { return b.name == spec.name; });
  if (body == scene.bodies().end()) return "";  // refused with its name before
  if (spec.support == "none") {
    body->support = fesd::SupportMode::kNone;
    return "";
  }
  const auto wall = std::find_if(scene.walls().begin(), scene.walls().end(),
                                 [&](const fesd::SceneWall& w) { return w.name == spec.support; });
  if (wall == scene.walls().end()) {
    return ": its support '" + spec.support +
           "' is no wall of the scene (only a wall holds a body; \"none\": it floats)";
  }
  body->support = fesd::SupportMode::kWall;
  body->support_wall = static_cast<int>(wall - scene.walls().begin());
  return "";
}

std::string applyTurning(const fesd_trajopt::BodySpec& spec, const fesd::TaskLimits& limits,
                         fesd::SceneBody& body, fesd::BodyTask& task) {
  for (const double value :
       {spec.initial_yaw, spec.target_yaw, spec.target_yaw_weight, spec.turning_radius}) {
    if (!std::isfinite(value)) return ": a yaw, yaw weight or turning radius is not finite";
  }
  if (spec.target_yaw_weight < 0.0 || spec.turning_radius < 0.0) {
    return ": target_yaw_weight and turning_radius must be >= 0";
  }
  const std::string spheres = requestedSpheres(spec, limits, body);
  if (!spheres.empty()) return spheres;
  const bool turns_in_urdf = body.turns;  // a link of spheres on a planar joint
  if (!spec.turns && !turns_in_urdf) {
    if (spec.initial_yaw != 0.0 || spec.target_yaw_weight > 0.0 || spec.turning_radius > 0.0) {
      return " has a yaw, a target yaw or a turning radius but does not turn (set turns)";
    }
    if (!body.spheres.empty()) body.radius = fesd::boundingRadius(body);
    return "";
  }
  if (body.actuated) return " turns and is actuated: only passive bodies turn";
  if (turns_in_urdf && !spec.override_initial_position && spec.initial_yaw != 0.0) {
    return " takes its yaw from the URDF: set override_initial_position for initial_yaw";
  }
  if (!turns_in_urdf || spec.override_initial_position) body.yaw = spec.initial_yaw;
  // The request's position is the spheres' centre of pressure (BodySpec.msg): their offsets
  // move, the body does not; a URDF link's spheres are where the URDF puts them: it moves.
  const Eigen::VectorXd position = body.position;
  fesd::turnAboutPressureCentre(body, spec.turning_radius);
  if (spec.add || spec.override_initial_position) body.position = position;
  body.radius = fesd::boundingRadius(body);
  task.target_yaw = spec.target_yaw;
  task.target_yaw_weight = spec.target_yaw_weight;
  return "";
}

/// The request's allowed_pairs as the task's; "" or why not.
std::string allowPairs(const std::vector<fesd_trajopt::ContactPair>& allowed,
                       fesd::SceneTask& task) {
  const std::vector<fesd::ContactPair> all = task.scene.allPairs();
  for (const fesd_trajopt::ContactPair& entry : allowed) {
    bool found = false;
    for (const fesd::ContactPair& pair : all) {
      const auto [a, b] = task.scene.pairSides(pair);
      if ((fesd::namesSide(entry.first, a) && fesd::namesSide(entry.second, b)) ||
          (fesd::namesSide(entry.second, a) && fesd::namesSide(entry.first, b))) {
        task.allowed_pairs.push_back(pair);
        found = true;
      }
    }
    if (!found) {
      return "allowed pair " + entry.first + "/" + entry.second +
             " names no pair of the scene (unknown name, two fixed items, or spheres that never "
             "pair)";
    }
  }
  return "";
}

/// The robot of `urdf_xml` (planar inferred unless the request forces it) into `read`; notes on
/// ignored shapes; "" or why not.
std::string readRobot(const NodeConfig& config, const SceneFields& request,
                      const std::string& urdf_xml, fesd::RobotForScene& read,
                      std::vector<std::string>& notes) {
  const fesd::PlanarChoice choice = !request.planar_override ? fesd::PlanarChoice::kInferred
                                    : request.planar         ? fesd::PlanarChoice::kPlanar
                                                             : fesd::PlanarChoice::kSpatial;
  fesd::KinematicModelOptions limits;
  limits.max_spheres = config.limits.max_spheres;
  read = fesd::robotForScene(urdf_xml, choice, limits);
  if (!read.error.empty()) return read.error;
  for (const std::string& shape : read.robot->ignored_shapes) {
    notes.push_back("collision " + shape + " is not a sphere and is ignored");
  }
  return "";
}

}  // namespace

std::string urdfSource(const NodeConfig& config, const SceneFields& request,
                       const ros::NodeHandle& node, std::string& xml) {
  if (!request.urdf.empty()) {
    xml = request.urdf;
    return "";
  }
  if (!request.urdf_param.empty()) {
    if (!node.getParam(request.urdf_param, xml) &&
        !ros::NodeHandle().getParam(request.urdf_param, xml)) {
      return "no parameter '" + request.urdf_param + "' holds a URDF";
    }
    return "";
  }
  if (config.scene_urdf.empty()) {
    return "no scene: give urdf or urdf_param, or start the node with ~scene_urdf";
  }
  xml = config.scene_urdf;
  return "";
}

std::string applySceneFields(const NodeConfig& config, const SceneFields& request,
                             fesd::SceneTask& task) {
  const int dim = task.scene.dimension();
  task.horizon = config.horizon;
  task.num_intervals = config.num_intervals;
  task.control_weight = config.control_weight;
  auto configure = [&](int b) {
    fesd::BodyTask body;
    configuredWorkspace(BodyConfig{}, dim, body);
    const auto found = config.bodies.find(task.scene.bodies()[b].name);
    if (found != config.bodies.end()) {
      const BodyConfig& c = found->second;
      task.scene.bodies()[b].actuated = c.actuated;
      body.max_speed = c.max_speed;
      body.target_weight = c.target_weight;
      if (!c.target.empty())
        body.target = Eigen::Map<const Eigen::VectorXd>(c.target.data(), c.target.size());
      configuredWorkspace(c, dim, body);
    }
    task.bodies.push_back(body);
  };
  for (size_t b = 0; b < task.scene.bodies().size(); ++b) configure(static_cast<int>(b));

  auto body_index = [&](const std::string& name) {
    for (size_t b = 0; b < task.scene.bodies().size(); ++b) {
      if (task.scene.bodies()[b].name == name) return static_cast<int>(b);
    }
    return -1;
  };
  for (const fesd_trajopt::BodySpec& spec : request.bodies) {
    const std::string who = "body '" + spec.name + "'";
    if (spec.name.empty()) {
      return "a body in the request has no name";
    }
    int b = body_index(spec.name);
    if (spec.add) {
      if (b >= 0) {
        return who + " already exists; set add only for new bodies";
      }
      if (!(spec.radius > 0.0) && spec.sphere_offsets.empty()) {
        return who + " is added with radius " + std::to_string(spec.radius) +
               " (must be > 0) and no spheres";
      }
      task.scene.bodies().push_back(
          {spec.name, spec.radius, coordinates(spec.initial_position, dim), false});
      configure(static_cast<int>(task.scene.bodies().size()) - 1);
      b = static_cast<int>(task.scene.bodies().size()) - 1;
    } else if (b < 0) {
      return who + " is not a link of the scene (unknown link); set add for a new body";
    }
    fesd::SceneBody& body = task.scene.bodies()[b];
    fesd::BodyTask& t = task.bodies[b];
    if (spec.radius < 0.0 || std::isnan(spec.radius)) {
      return who + " has radius " + std::to_string(spec.radius) + " (must be > 0)";
    }
    if (spec.radius > 0.0 && !body.spheres.empty() && !spec.add) {
      return who + " carries " + std::to_string(body.spheres.size()) +
             " collision spheres in the URDF: its size comes from them, not a radius";
    }
    if (spec.radius > 0.0) body.radius = spec.radius;
    if (spec.override_initial_position) body.position = coordinates(spec.initial_position, dim);
    if (spec.role == fesd_trajopt::BodySpec::ROLE_ACTUATED) body.actuated = true;
    if (spec.role == fesd_trajopt::BodySpec::ROLE_PASSIVE) body.actuated = false;
    if (spec.role > fesd_trajopt::BodySpec::ROLE_PASSIVE) {
      return who + " has an unknown role " + std::to_string(spec.role);
    }
    if (spec.max_speed < 0.0 || std::isnan(spec.max_speed)) {
      return who + ": max_speed must be >= 0";
    }
    if (spec.max_speed > 0.0) t.max_speed = spec.max_speed;
    if (spec.clear_target) {
      t.target.resize(0);
      t.target_weight = 0.0;
    }
    if (spec.target_weight != 0.0) {
      t.target = coordinates(spec.target, dim);
      t.target_weight = spec.target_weight;
    }
    const std::string turning = applyTurning(spec, config.limits, body, t);
    if (!turning.empty()) return who + turning;
    for (const auto& [values, bounds, name] :
         {std::make_tuple(&spec.workspace_lower, &t.workspace_lower, "workspace_lower"),
          std::make_tuple(&spec.workspace_upper, &t.workspace_upper, "workspace_upper")}) {
      const std::string problem = requestedBounds(*values, dim, *bounds);
      if (!problem.empty()) {
        return who + ": " + name + " " + problem;
      }
    }
  }
  for (const fesd_trajopt::Obstacle& o : request.obstacles) {
    task.scene.obstacles().push_back({o.name, o.radius, coordinates(o.position, dim)});
  }
  for (const fesd_trajopt::Wall& w : request.walls) {
    Eigen::VectorXd normal(dim);
    normal(0) = w.normal.x;
    normal(1) = w.normal.y;
    if (dim == 3) normal(2) = w.normal.z;
    const double length = normal.norm();
    if (!(length > 0.0) || !std::isfinite(length)) {
      return "wall '" + w.name + "' has no usable normal (zero, NaN or infinite)";
    }
    task.scene.walls().push_back({w.name, normal / length, w.offset / length});
  }
  for (const fesd_trajopt::BodySpec& spec : request.bodies) {
    const std::string problem = applySupport(spec, task.scene);
    if (!problem.empty()) return "body '" + spec.name + "'" + problem;
  }
  std::set<std::string> names;
  for (const auto& b : task.scene.bodies()) names.insert(b.name);
  for (const auto& o : task.scene.obstacles()) {
    if (o.name.empty() || !names.insert(o.name).second) {
      return "obstacle name '" + o.name + "' is empty or already used";
    }
  }
  for (const auto& w : task.scene.walls()) {
    if (w.name.empty() || !names.insert(w.name).second) {
      return "wall name '" + w.name + "' is empty or already used";
    }
  }
  return "";
}

TaskBuild buildTask(const NodeConfig& config, const SceneFields& request, const RobotFields& robot,
                    const ros::NodeHandle& node) {
  TaskBuild build;
  std::string xml;
  build.error = urdfSource(config, request, node, xml);
  if (!build.error.empty()) return build;
  fesd::SceneTask& task = build.task;
  std::optional<fesd::RobotForScene> read;
  if (isRobotUrdf(xml)) {
    build.error = readRobot(config, request, xml, read.emplace(), build.notes);
    if (!build.error.empty()) return build;
    task.scene = fesd::Scene(read->dimension);
    task.scene.bodies() = read->free_bodies;  // the URDF's pucks, configured like its discs
  } else {
    if (!robot.joints.empty()) {
      build.error = "joints are given, but the scene's URDF has no moving joints";
      return build;
    }
    const bool planar = request.planar_override ? request.planar : config.planar;
    fesd::UrdfScene urdf = fesd::sceneFromUrdf(xml, planar);
    if (!urdf.error.empty()) {
      build.error = urdf.error;
      return build;
    }
    for (const std::string& link : urdf.ignored_links) {
      build.notes.push_back("link '" + link + "' has no usable collision geometry and is ignored");
    }
    for (const std::string& shape : urdf.ignored_shapes) {
      build.notes.push_back("collision " + shape + " is not a sphere and is ignored");
    }
    task.scene = urdf.scene;
    build.planar_joints = urdf.planar_joints;
  }
  build.error = applySceneFields(config, request, task);
  if (build.error.empty() && read) build.error = applyRobotFields(*read, robot, node, task);
  if (build.error.empty()) build.error = allowPairs(request.allowed_pairs, task);
  if (!build.error.empty() || !read) return build;
  // applySceneFields writes "no bounds" as +-infinity; a robot task wants none at all (finite
  // ones are refused by validateTask, naming the body).
  constexpr double kInf = std::numeric_limits<double>::infinity();
  for (fesd::BodyTask& body : task.bodies) {
    if ((body.workspace_lower.array() == -kInf).all()) body.workspace_lower.resize(0);
    if ((body.workspace_upper.array() == kInf).all()) body.workspace_upper.resize(0);
  }
  return build;
}

}  // namespace fesd_ros
