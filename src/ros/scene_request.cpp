#include "scene_request.h"

#include <cmath>
#include <limits>
#include <set>

#include "fesd_trajopt/scene/urdf_scene.h"

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

std::string otherName(const fesd::DiscScene& scene, const fesd::ContactPair& pair) {
  switch (pair.kind) {
    case fesd::ContactPair::Kind::kBody:
      return scene.bodies()[pair.other].name;
    case fesd::ContactPair::Kind::kObstacle:
      return scene.obstacles()[pair.other].name;
    case fesd::ContactPair::Kind::kWall:
      return scene.walls()[pair.other].name;
  }
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
      if (!(spec.radius > 0.0)) {
        return who + " is added with radius " + std::to_string(spec.radius) + " (must be > 0)";
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

TaskBuild buildTask(const NodeConfig& config, const SceneFields& request,
                    const ros::NodeHandle& node) {
  TaskBuild build;
  std::string xml;
  build.error = urdfSource(config, request, node, xml);
  if (!build.error.empty()) return build;
  const bool planar = request.planar_override ? request.planar : config.planar;
  fesd::UrdfScene urdf = fesd::sceneFromUrdf(xml, planar);
  if (!urdf.error.empty()) {
    build.error = urdf.error;
    return build;
  }
  for (const std::string& link : urdf.ignored_links) {
    build.notes.push_back("link '" + link + "' has no usable collision geometry and is ignored");
  }
  fesd::SceneTask& task = build.task;
  task.scene = urdf.scene;
  build.error = applySceneFields(config, request, task);
  if (!build.error.empty()) return build;
  const std::vector<fesd::ContactPair> all = task.scene.allPairs();
  for (const fesd_trajopt::ContactPair& allowed : request.allowed_pairs) {
    bool found = false;
    for (const fesd::ContactPair& pair : all) {
      const std::string a = task.scene.bodies()[pair.body].name, b = otherName(task.scene, pair);
      if ((a == allowed.first && b == allowed.second) ||
          (a == allowed.second && b == allowed.first)) {
        task.allowed_pairs.push_back(pair);
        found = true;
      }
    }
    if (!found) {
      build.error = "allowed pair " + allowed.first + "/" + allowed.second +
                    " names no pair of the scene (unknown name, or two fixed items)";
      return build;
    }
  }
  return build;
}

}  // namespace fesd_ros
