#include "node_config.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <thread>

#include <XmlRpcValue.h>

namespace fesd_ros {
namespace {

double number(const XmlRpc::XmlRpcValue& value, const std::string& what) {
  if (value.getType() == XmlRpc::XmlRpcValue::TypeDouble) return static_cast<double>(value);
  if (value.getType() == XmlRpc::XmlRpcValue::TypeInt) return static_cast<int>(value);
  throw std::runtime_error("parameter " + what + " must be a number");
}

BodyConfig bodyConfig(XmlRpc::XmlRpcValue& value, const std::string& name) {
  const std::string where = "bodies/" + name;
  if (value.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
    throw std::runtime_error("parameter " + where + " must be a map");
  }
  BodyConfig config;
  for (auto& [key, item] : value) {
    if (key == "actuated") {
      if (item.getType() != XmlRpc::XmlRpcValue::TypeBoolean) {
        throw std::runtime_error("parameter " + where + "/actuated must be true or false");
      }
      config.actuated = static_cast<bool>(item);
    } else if (key == "max_speed") {
      config.max_speed = number(item, where + "/max_speed");
    } else if (key == "target_weight") {
      config.target_weight = number(item, where + "/target_weight");
    } else if (key == "target") {
      if (item.getType() != XmlRpc::XmlRpcValue::TypeArray) {
        throw std::runtime_error("parameter " + where + "/target must be a list");
      }
      for (int i = 0; i < item.size(); ++i) config.target.push_back(number(item[i], where));
    } else if (key == "workspace") {
      if (item.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
        throw std::runtime_error("parameter " + where + "/workspace must be a map");
      }
      for (auto& [bound, limit] : item) {
        static const char* known[] = {"x_min", "x_max", "y_min", "y_max", "z_min", "z_max"};
        if (std::find(std::begin(known), std::end(known), bound) == std::end(known)) {
          throw std::runtime_error("parameter " + where + "/workspace/" + bound +
                                   " is not one of x_min, x_max, y_min, y_max, z_min, z_max");
        }
        config.workspace[bound] = number(limit, where + "/workspace/" + bound);
      }
    } else {
      throw std::runtime_error("unknown parameter " + where + "/" + key);
    }
  }
  return config;
}

}  // namespace

NodeConfig loadNodeConfig(const ros::NodeHandle& node) {
  NodeConfig c;
  node.param("frame_id", c.frame_id, c.frame_id);
  node.param("planar", c.planar, c.planar);
  node.param("horizon", c.horizon, c.horizon);
  node.param("num_intervals", c.num_intervals, c.num_intervals);
  node.param("control_weight", c.control_weight, c.control_weight);
  node.param("num_elements", c.num_elements, c.num_elements);
  node.param("num_stages", c.num_stages, c.num_stages);
  std::string method = "fesd";
  node.param("method", method, method);
  if (method != "fesd" && method != "standard") {
    throw std::runtime_error("parameter method must be fesd or standard, got '" + method + "'");
  }
  c.fesd = method == "fesd";
  node.param("complementarity_tolerance", c.complementarity_tolerance, c.complementarity_tolerance);
  node.param("wall_time_budget", c.wall_time_budget, c.wall_time_budget);
  node.param("verification/num_stages", c.verification_stages, c.verification_stages);
  node.param("verification/num_elements", c.verification_elements, c.verification_elements);
  node.param("target_accuracy", c.target_accuracy, c.target_accuracy);
  if (!(c.target_accuracy >= 0.0) || !std::isfinite(c.target_accuracy)) {
    throw std::runtime_error("parameter target_accuracy must be finite and >= 0 (0: off)");
  }
  node.param("playback_rate", c.playback_rate, c.playback_rate);
  std::string pairs = "lazy";
  node.param("contact_pairs", pairs, pairs);
  if (pairs != "lazy" && pairs != "all_in_reach") {
    throw std::runtime_error("parameter contact_pairs must be lazy or all_in_reach, got '" + pairs +
                             "'");
  }
  c.lazy_pairs = pairs == "lazy";
  node.param("contact_margin", c.contact_margin, c.contact_margin);
  if (!(c.contact_margin >= 0.0) || !std::isfinite(c.contact_margin)) {
    throw std::runtime_error("parameter contact_margin must be finite and >= 0");
  }
  node.param("robot_all_pairs_up_to", c.robot_all_pairs_up_to, c.robot_all_pairs_up_to);
  if (c.robot_all_pairs_up_to < 0) {
    throw std::runtime_error("parameter robot_all_pairs_up_to must be >= 0");
  }
  std::string mpcc_method = fesd::methodName(c.mpcc_method);
  node.param("mpcc_method", mpcc_method, mpcc_method);
  if (!fesd::parseMethod(mpcc_method, c.mpcc_method)) {
    throw std::runtime_error("parameter mpcc_method must be homotopy or active_set, got '" +
                             mpcc_method + "'");
  }
  node.param("linear_solver", c.linear_solver, c.linear_solver);
  if (c.linear_solver != "ldlt" && c.linear_solver != "mumps") {
    throw std::runtime_error("parameter linear_solver must be ldlt or mumps, got '" +
                             c.linear_solver + "'");
  }
  node.param("solver_threads", c.solver_threads, c.solver_threads);
  if (c.solver_threads < 0) throw std::runtime_error("parameter solver_threads must be >= 0");
  if (c.solver_threads == 0) c.solver_threads = std::max(1u, std::thread::hardware_concurrency());
  node.param("limits/max_bodies", c.limits.max_bodies, c.limits.max_bodies);
  node.param("limits/max_spheres", c.limits.max_spheres, c.limits.max_spheres);
  node.param("limits/max_obstacles", c.limits.max_obstacles, c.limits.max_obstacles);
  node.param("limits/max_walls", c.limits.max_walls, c.limits.max_walls);
  node.param("limits/max_intervals", c.limits.max_intervals, c.limits.max_intervals);
  node.param("limits/max_elements", c.limits.max_elements, c.limits.max_elements);
  node.param("limits/max_stages", c.limits.max_stages, c.limits.max_stages);
  node.param("limits/max_horizon", c.limits.max_horizon, c.limits.max_horizon);
  node.param("limits/max_solver_mib", c.limits.max_solver_mib, c.limits.max_solver_mib);
  node.param("limits/max_sensitivity_entries", c.max_sensitivity_entries,
             c.max_sensitivity_entries);
  node.param("scene_urdf", c.scene_urdf, std::string());
  node.param("interactive_targets", c.interactive_targets, c.interactive_targets);
  XmlRpc::XmlRpcValue bodies;
  if (node.getParam("bodies", bodies)) {
    if (bodies.getType() != XmlRpc::XmlRpcValue::TypeStruct) {
      throw std::runtime_error("parameter bodies must be a map from link names to settings");
    }
    for (auto& [name, value] : bodies) c.bodies[name] = bodyConfig(value, name);
  }
  return c;
}

}  // namespace fesd_ros
