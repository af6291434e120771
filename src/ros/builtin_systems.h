#pragma once

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/model/dynamics_model.h"

namespace fesd_ros {

/// A system ~simulate knows by name: its model, start, horizon and names.
struct BuiltinSystem {
  std::shared_ptr<const fesd::DynamicsModel> model;
  Eigen::VectorXd initial_state;
  double horizon;
  std::vector<std::string> state_names;
  std::vector<std::string> constraint_names;  ///< the switches' second side, per constraint
};

/// circle_example (Pozharskiy et al. 2024, Example 1), two_minus_sign (x' = 2 - sign(x) from
/// x0 = -1 on [0, 2], Nurkanovic et al. 2024 OCP (56)), spiral (their eq. 47) or sliding
/// (sliding_example); nothing for another name.
std::optional<BuiltinSystem> builtinSystem(const std::string& name);

}  // namespace fesd_ros
