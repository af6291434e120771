#pragma once

#include <memory>

#include <Eigen/Dense>

#include "fesd_trajopt/core/butcher_tableau.h"
#include "fesd_trajopt/core/dynamics_model.h"
#include "fesd_trajopt/core/smooth_function.h"

namespace fesd {

/// An optimal control problem on a nonsmooth system (a PDS as DcsModel, a Filippov system as
/// StewartModel):
///   min  int_0^T L(x, u) dt + R(x(T))
///   s.t. x(0) = x0 (or x0_lower <= x(0) <= x0_upper), the system's dynamics, u piecewise constant
///   on num_intervals equal intervals,
///        u_lower <= u <= u_upper, x_lower <= x <= x_upper, g_p(x, u) <= 0, g_t(x(T)) <= 0.
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
};

/// How the cross-complementarity conditions (seed 000, eq. 8) are imposed.
enum class CrossComplementarity {
  kElementSums,  ///< one product of sums per element and constraint (few, denser rows)
  kStagePairs,   ///< one product per pair of points (many, sparser rows)
};

/// Step equilibration of a Filippov system (seed 001, eq. 31): (h_n - h_{n-1}) eta_n = 0 with
/// the switch indicator eta_n, or with tanh(eta_n) for a better scaling; or none (the steps
/// are then free wherever nothing switches). A PDS always uses its own exact form.
enum class StepEquilibration { kNone, kIndicator, kTanhIndicator };

/// How a PDS discretisation imposes step equilibration (seed 000, Sec. III-C).
enum class PdsStepEquilibration {
  /// Relaxed NLPs carry only the vanishing step regulariser; active-set polishing imposes the
  /// combinatorial meaning of Table I exactly: h_{n-1} = h_n at every boundary without a switch.
  /// Measured on the showcase (N = 40): a third of the variables, half of the rows and 320 of
  /// the 560 complementarity pairs are the paper's auxiliaries, and dropping them from the
  /// relaxed NLPs cut an Ipopt iteration from about 37 ms to 12 ms with the same iterations.
  kPolishing,
  /// The paper's formulation in every NLP: nu from the KKT conditions of the max LP (auxiliary
  /// variables and complementarity pairs) and the big-M bound |h_{n-1} - h_n| <= nu M.
  kBigM,
};

struct DiscretizationOptions {
  CollocationFamily family = CollocationFamily::kRadauIIA;
  int num_stages = 2;
  int num_elements = 2;          ///< finite elements per control interval
  bool switch_detection = true;  ///< FESD; false gives the standard fixed-step method
  CrossComplementarity cross_complementarity = CrossComplementarity::kElementSums;
  double step_bound = 1.0;  ///< gamma_h: (1 - gamma_h) h0 <= h_n <= (1 + gamma_h) h0
  PdsStepEquilibration pds_step_equilibration = PdsStepEquilibration::kPolishing;
  /// kBigM only: M of the bound |h_{n-1} - h_n| <= nu_n M, in units of h0. At a release
  /// c leaves the boundary quadratically, so nu is only O(delta^2) when the element after it is
  /// delta long, and M must exceed h0 / delta^2 for every delta the grid may need. With active-
  /// set polishing (MpccSolver) nu is exactly 0 away from switches, so a large M costs no
  /// equality there; in the relaxed NLPs the vanishing regulariser keeps the steps equal.
  double equilibration_big_m = 1e9;
  /// rho of the regulariser  rho * sigma * sum_n ((h_n - h_{n-1}) / h0)^2  within each control
  /// interval. The relaxed NLPs (sigma > 0) leave the steps partly free; this keeps their path
  /// away from collapsed elements. At sigma -> 0 it vanishes and only the exact step
  /// equilibration remains. 0 switches it off.
  double step_regularization = 1.0;
  StepEquilibration filippov_step_equilibration = StepEquilibration::kIndicator;
  /// r of the relaxed step equilibration |((h_n - h_{n-1}) / h0) eta_n| <= r sigma of a
  /// Filippov system. With r = 1 the relaxed NLPs of example (47) on coarse grids, whose
  /// switch starts inside an element, could not move their steps and ended infeasible; with
  /// r = 1e3 some simulation steps of OCP (61)'s controls that leave a sliding mode did. So
  /// the relaxed NLPs are guided by the step regulariser above, like the PDS's big M, and
  /// polishing imposes eq. 31 exactly (h_{n-1} = h_n wherever eta_n cannot vanish).
  double filippov_equilibration_relaxation = 1e6;
};

}  // namespace fesd
