#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fesd_trajopt/discretization/discretization.h"
#include "fesd_trajopt/integrator/active_set_step.h"
#include "fesd_trajopt/model/dynamics_model.h"
#include "fesd_trajopt/solver/mpcc_solver.h"

namespace fesd {

inline HomotopyOptions steepHomotopy() {
  HomotopyOptions options;
  options.sigma_reduction = 0.01;
  // A step has no objective: a pair left biactive could end with both sides positive.
  options.polish_biactive_fraction = 0.0;
  return options;
}

/// The retry: a gentler homotopy without the step regulariser, i.e. another path.
inline HomotopyOptions retryHomotopy() {
  HomotopyOptions options;
  options.vanishing_terms_weight = 0.0;
  options.polish_biactive_fraction = 0.0;
  return options;
}

struct SimulationOptions {
  DiscretizationOptions discretization;
  /// Simulation steps are small MPCCs solved one after another; a steeper homotopy
  /// (kappa = 0.01) needs about a quarter fewer Ipopt iterations on them than the OCP default.
  HomotopyOptions homotopy = steepHomotopy();
  /// A step whose homotopy fails is solved once more along another path: kappa = 0.1 and no
  /// step regulariser. Seen needed where a release falls just before a step's end: the
  /// relaxed solutions can settle with the release inside the last, tiny element, from where
  /// no tighter relaxation is feasible.
  HomotopyOptions retry_homotopy = retryHomotopy();
  double activity_tolerance = kDefaultActivityTolerance;
  /// Depth, in state units, beyond which an element's collocation polynomial counts as passing
  /// through a constraint (findUnresolvedSwitches). The default suits lengths of order one; a
  /// resolved slide along a curve bends off it in proportion to the scene's size, so scale it
  /// with the lengths of the scene (measured: R = 1e3 flags a resolved slide at the default).
  double penetration_tolerance = kDefaultPenetrationTolerance;
  /// Seconds for the whole simulation: each step's homotopy gets what is left; a step that runs
  /// out ends the simulation with kTimeout (the steps before it are kept).
  double wall_time_budget = std::numeric_limits<double>::infinity();
  /// Start each step from the previous step's solution translated to the new start state
  /// (otherwise from a constant guess).
  bool reuse_previous_step = true;
  /// A step whose solution is not exact (neither homotopy converges, or no active set can be
  /// polished; not for lack of time) is solved in four parts, 0.1, 0.4, 0.4 and 0.1 of its
  /// length, each with num_elements elements, recursively up to this many levels. Measured on the
  /// random push scenes (fesd_bench simulation-sweep): most such steps held more switches than
  /// their element boundaries can place (a chain of contacts, a body meeting a wall), an infeasible
  /// FESD step rather than a solver failure; others had a switch within 1e-3 of their start or
  /// end, which needs a tiny element (the short end parts make it ten times longer relative to
  /// its part). A part at the last level that still does not converge is integrated with fixed
  /// steps (SimulationResult::fixed_step_parts). 0: no splitting; such a step fails (or keeps its
  /// unpolished solution).
  int max_step_splits = 4;
  /// A part is solved again with twice the elements, and that solution kept if it is exact and
  /// no element exceeds max_element_stretch times the coarser nominal length, where the part's
  /// own solution is exact but stretches an element beyond max_element_stretch times its nominal
  /// length (part length / num_elements), or is not exact and the part cannot be split any
  /// further (more element boundaries before fixed steps; splitting first is more accurate:
  /// measured 20 to 200 times on some random push scenes). false: every part keeps num_elements
  /// elements, the discretisation of the papers.
  bool refine_elements = true;
  /// Why refine stretched elements: FESD places a switch at an element boundary, so the other
  /// element can grow to nearly twice its nominal length, and the error with it by up to
  /// 2^(2 n_s) from one grid to the next (measured on the random push scenes: a contact 0.08
  /// into a step left one element 1.8 times too long, the error 140 times above both
  /// neighbouring grids'). On twice the elements no element exceeds its nominal length.
  double max_element_stretch = 1.05;
  /// An exact but stretched part is refined by the homotopy too when its active sets find no
  /// solution on twice the elements. false: by the active sets only (a plan's verification:
  /// on the cluttered scenes such homotopies cost 100-1100 Ipopt iterations a part, for a
  /// reference that is finer than the plan either way).
  bool refine_by_homotopy = true;
  /// A step or part whose active sets find no solution is split (max_step_splits) before its
  /// homotopy is tried: only a part that cannot be split further takes the homotopy. Such a part
  /// holds more switches than element boundaries, or a contact and the release it causes at one
  /// instant (the force jumps, which cross-complementarity forbids): the homotopy cannot place
  /// the second kind either. false: each part's homotopy first.
  bool split_before_homotopy = false;
  /// Solve each part first as the smooth square system of its predicted active set, by Newton's
  /// method, locating switches from violated signs (solveByActiveSets); the homotopy only where
  /// that finds no exact FESD solution. false: the homotopy for every part, for comparison.
  bool active_set_steps = true;
  /// Also the derivatives of the states at the step ends and of the switch times by the start
  /// state and the controls (SimulationResult::sensitivities): exact, by the implicit function
  /// theorem on each part's FESD system at its solution.
  bool sensitivities = false;
};

/// The derivatives of a simulation (SimulationOptions::sensitivities) by its start state x0 and
/// the controls u_0 .. u_{N-1} of its N steps (u_j acts on step j alone; a control held over all
/// steps has the sum of their blocks). With switch detection (FESD) they converge to those of
/// the exact flow across switches (Nurkanovic et al. 2024, Sec. 4.5): the switch times are
/// unknowns of each step's system. Without it (time-stepping) they are the derivatives of the
/// discrete map, which do not converge across switches: for comparison only.
struct SimulationSensitivities {
  /// Per step end k: d x(t_k) / d (x0, u_0, .., u_{N-1}), n_x x (n_x + N n_u); NaN from the
  /// first step whose derivatives are not defined on.
  std::vector<Eigen::MatrixXd> states;
  /// Per switch of the trajectory, in order: d t / d (x0, u_0, .., u_{N-1}); NaN after the
  /// first undefined part.
  std::vector<Eigen::RowVectorXd> switch_times;
  int defined_steps = 0;      ///< states[0 .. defined_steps) are defined
  std::string why_undefined;  ///< for the steps from defined_steps on
};

struct SimulationResult {
  SolveStatus status = SolveStatus::kSolverError;
  std::string message;
  Trajectory trajectory;  ///< element boundaries and stage values of all steps, with switches
  MpccReport totals;      ///< summed iterations and times, worst complementarity residual
  std::vector<std::vector<HomotopyStep>> step_histories;  ///< each step's homotopy
  int completed_steps = 0;
  int retried_steps = 0;  ///< steps (or parts of steps) that needed the retry homotopy
  int split_steps = 0;    ///< steps solved in parts (SimulationOptions::max_step_splits)
  int refined_parts = 0;  ///< parts solved with twice the elements (max_element_stretch)
  /// The deepest parts that FESD could not solve, integrated with fixed steps instead (their
  /// switches are reported unresolved).
  int fixed_step_parts = 0;
  /// How the parts kept in the trajectory were solved: their predicted active set held, their
  /// switches were located by Newton solves, or by the homotopy.
  int predicted_parts = 0, located_parts = 0, homotopy_parts = 0;
  int newton_iterations = 0;              ///< over all active-set attempts, kept or not
  SimulationSensitivities sensitivities;  ///< SimulationOptions::sensitivities
};

/// A simulation by multiple shooting (FesdIntegrator::shoot): each step from a start state of its
/// own, as a plan is verified interval by interval.
struct ShootingResult {
  SolveStatus status = SolveStatus::kSolverError;
  std::string message;
  std::vector<Trajectory> steps;  ///< per step solved, its trajectory (times from k h)
  /// With SimulationOptions::sensitivities, per step solved: d x(end) / d x(start), n_x x n_x;
  /// empty where not defined (why_undefined says why).
  std::vector<Eigen::MatrixXd> transitions;
  std::vector<std::string> why_undefined;
  MpccReport totals;  ///< summed over the steps
};

/// Simulates a nonsmooth system (any DynamicsModel) with FESD: num_steps steps of length horizon /
/// num_steps, each with num_elements finite elements, solved one after another as small MPCCs.
class FesdIntegrator {
 public:
  FesdIntegrator(std::shared_ptr<const DynamicsModel> model, SimulationOptions options);

  /// `controls` holds one control per step, a single control for all steps, or nothing when
  /// the model has no controls. Stops at the first step that does not converge. `reference`
  /// (optional): a trajectory the run is expected to stay near, one control interval per step
  /// (a plan executed open loop): its forces predict each part's active sets first, then the
  /// run's own history does.
  SimulationResult simulate(const Eigen::VectorXd& x0, double horizon, int num_steps,
                            const std::vector<Eigen::VectorXd>& controls = {},
                            const Trajectory* reference = nullptr);

  /// Step k of length step_length from starts[k] under controls[k] (none when the model has no
  /// controls), each from its own start rather than from the end of the step before; stops at
  /// the first step that does not converge. The solvers and step problems are shared.
  /// `reference` (optional): a trajectory near the one sought with one control interval per step
  /// (a plan being verified, in the model's states and pairs), whose forces predict every part's
  /// active sets and how each start is reached (the solution from a start does not depend on
  /// them; finding it by Newton's method does).
  ShootingResult shoot(const std::vector<Eigen::VectorXd>& starts, double step_length,
                       const std::vector<Eigen::VectorXd>& controls,
                       const Trajectory* reference = nullptr);

 private:
  class Run;
  std::shared_ptr<const DynamicsModel> model_;
  SimulationOptions options_;
};

}  // namespace fesd
