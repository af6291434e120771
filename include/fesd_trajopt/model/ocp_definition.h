#pragma once

#include <memory>

#include <Eigen/Dense>

#include "fesd_trajopt/function/smooth_function.h"
#include "fesd_trajopt/model/dynamics_model.h"

namespace fesd {

/// An optimal control problem on a nonsmooth system (a PDS as DcsModel, a Filippov system as
/// StewartModel):
///   min  int_0^T L(x, u) dt + R(x(T))
///   s.t. x(0) = x0 (or x0_lower <= x(0) <= x0_upper), the system's dynamics, u piecewise constant
///   on num_intervals equal intervals,
///        u_lower <= u <= u_upper, x_lower <= x <= x_upper, g_p(x, u) <= 0, g_t(x(T)) <= 0,
///        g_f(x, u, lambda) <= g_f_upper.
/// Every function is optional; with none and fixed controls this is a simulation.
struct OcpDefinition {
  std::shared_ptr<const DynamicsModel> model;
  Eigen::VectorXd initial_state;
  /// A free start within these bounds (initial_state is then only the guess); empty: fixed.
  /// Only Filippov models support it.
  Eigen::VectorXd initial_state_lower, initial_state_upper;
  double horizon = 1.0;
  int num_intervals = 1;
  Eigen::VectorXd control_lower, control_upper;            ///< size n_u, or empty for unbounded
  Eigen::VectorXd state_lower, state_upper;                ///< at every stage point; empty for none
  std::shared_ptr<const SmoothFunction> lagrange_cost;     ///< L on (x, u), scalar
  std::shared_ptr<const SmoothFunction> mayer_cost;        ///< R on x, scalar
  std::shared_ptr<const SmoothFunction> path_constraints;  ///< g_p on (x, u), <= 0
  std::shared_ptr<const SmoothFunction> terminal_constraints;  ///< g_t on x, <= 0
  bool path_constraints_at_all_stages = false;                 ///< else only at element boundaries
  /// g_f on a PDS's (x, u, lambda), <= force_upper at every stage point: forces a plan must not
  /// need (a support that would have to pull, Scene::supportLiftRates). A simulation has none.
  std::shared_ptr<const SmoothFunction> force_constraints;
  Eigen::VectorXd force_upper;  ///< per output of g_f; empty: 0
};

}  // namespace fesd
