#pragma once

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/planning/accuracy_rung.h"
#include "fesd_trajopt/planning/plan_verification.h"
#include "fesd_trajopt/planning/push_plan.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "fesd_trajopt/scene/warm_start.h"

namespace fesd {

/// A pair whose gap a solve keeps along the whole of every element of a control interval (gap
/// guards between the stage points), where a plan grazed it.
struct PairInterval {
  ContactPair pair;  ///< the full task's indices
  int interval = 0;
  bool operator==(const PairInterval& other) const {
    return pair == other.pair && interval == other.interval;
  }
};

/// A scene task solved or simulated, in the full scene's terms. A task that is refused
/// (`invalid`) or cannot be met (`infeasible`) is never solved: status and trajectory stay
/// at their defaults.
struct SceneOutcome {
  std::string invalid;     ///< why validateTask refused the task; "" when valid
  std::string infeasible;  ///< why infeasibility() says the goals cannot be met; "" otherwise
  std::vector<PairDecision> decisions;  ///< every pair of the scene: modelled or why not
  std::vector<ContactPair> modelled;    ///< the last NLP's constraints, in order
  std::vector<int> moving_bodies;       ///< the bodies with states (MovingPart::bodies)
  int pusher_sphere = -1;  ///< the robot sphere the first guess pushes with (planRobotGuess)
  /// The first guess's push plan of free bodies (planPushes): what it foresaw, for display.
  std::vector<PushLeg> planned_legs;
  std::vector<Transit> planned_transits;
  SolveStatus status = SolveStatus::kSolverError;
  std::string message;
  OcpStart start = OcpStart::kConstant;  ///< the solve's start (not for simulations)
  Trajectory trajectory;                 ///< of the full scene: frozen bodies at their start
  MpccReport report;                     ///< the solve's, or a simulation's totals
  NlpSizes sizes;                        ///< the solve's NLP (a simulation's step NLP: none)
  /// The smallest gap of the modelled pairs at the element boundaries (negative: penetration).
  double boundary_gap = std::numeric_limits<double>::quiet_NaN();
  bool verified = false;
  Verification verification;  ///< when verified
  PlanStructure structure;    ///< of the solve (not for simulations)
  /// A warm start was asked for but the solve started cold (or fell back to cold): why.
  std::string cold_start_reason;
  /// The first round started from `previous` (later lazy-pair rounds start from the round
  /// before, so `start` alone does not tell).
  bool warm_started = false;
  std::vector<AccuracyRung> refinements;  ///< solveToAccuracy's rungs, in order
  /// The pairs and intervals whose gaps the last NLP kept along whole elements.
  std::vector<PairInterval> held_grazes;
  /// Grazes' deepest points held exactly on this grid (element and fraction), besides held_grazes.
  std::vector<Graze> guard_points;
  /// The plan's own grazes left (planGrazes: cuts into a body between stage points).
  std::vector<Graze> grazes;
  int graze_rounds = 0;  ///< solves that added gap guards for the plan's grazes
  /// The solve started from a plan on a coarser rung (SceneSolveOptions::refine) and kept it.
  bool refined_plan = false;
  /// What a solve that started from a plan (OcpStart::kTrajectory) started from: "previous
  /// round", "coarser rung's plan", "previous plan after k interval(s)".
  std::string plan_source;
  /// A simulation's sensitivities (SimulationOptions::sensitivities), by the full scene's state.
  SimulationSensitivities sensitivities;
  /// Solves with a growing set of modelled pairs (SceneSolveOptions::lazy_pairs): 1 when the
  /// first set held; 0 for simulations.
  int pair_rounds = 0;
  /// Per body: its end position's distance from its target (NaN without a target).
  std::vector<double> target_distances;
  /// Per body: |yaw(T) - target_yaw| of a turning body with a yaw target (NaN without one).
  std::vector<double> target_yaw_distances;
  /// Per joint: |q_j(T) - target| (NaN without a target).
  std::vector<double> joint_target_distances;
  /// The length the task was solved in (lengthScale, in the task's units; 1 when solved in its
  /// units as given): the report's residuals and tolerances are of the problem in those units.
  double length_scale = 1.0;
  /// Per body: the wall it slid on (Scene::supportOf), -1 when it floated.
  std::vector<int> supports;
  /// Bodies whose support a plan would have had to pull (supportLifts): from the round after, the
  /// plan pushes them only as their support holds them (BodyTask::hold_on_support); a finer rung
  /// or a replan starts so.
  std::vector<int> held_on_support;
  /// The first guess's residual in the NLP's equations (NlpAssembly::equalityResidual at its
  /// point on the first round's grid): how far it is from dynamics consistent with its contacts.
  /// NaN when the solve started from a previous solution (and its guess was not needed).
  double guess_residual = std::numeric_limits<double>::quiet_NaN();

  bool solved() const { return invalid.empty() && infeasible.empty(); }
  int modelledPairs() const {
    return static_cast<int>(std::count_if(decisions.begin(), decisions.end(),
                                          [](const PairDecision& d) { return d.modelled; }));
  }
  int checkedPairs() const {
    return static_cast<int>(std::count_if(decisions.begin(), decisions.end(),
                                          [](const PairDecision& d) { return d.checked; }));
  }
};

/// Why `previous` cannot warm-start `now` (a task whose NLP is built: structure and sizes set):
/// not a successful solve, warmStartMismatch, or other NLP sizes; "" when it can.
std::string warmStartRefusal(const SceneOutcome& previous, const SceneOutcome& now);

/// Options of a scene solve. Their lengths (graze depth, accuracy targets) and tolerances are in
/// units of the task's length scale (lengthScale) unless length_scaling is off; margins are
/// relative to a pair's size.
struct SceneSolveOptions {
  /// Solve in units of the task's lengthScale and answer in the task's (solveInLengthUnits): a
  /// scene and its copy in other units are one NLP, whose constants were tuned at that scale.
  /// false: in the task's units as given (as before; for comparisons).
  bool length_scaling = true;
  OcpOptions ocp;           ///< discretisation and homotopy (its wall-time budget covers all)
  bool prune_pairs = true;  ///< model only the pairs that can touch (decidePairs); else all
  /// Lazy pairs: of the pairs in reach, model first only those the first guess calls for
  /// (pairsTheGuessNeeds), check every other one on the solution (between element boundaries
  /// too: densePath, smallestGap), add those that come within the margin and solve again from
  /// that solution, until none does. Then the answer solves the problem with every pair in
  /// reach. false: every pair in reach is modelled from the start.
  bool lazy_pairs = true;
  /// With lazy_pairs, a task with at most this many pairs in reach models them all anyway (few
  /// pairs are cheap, and lazy rounds can end in other local optima: on the arm push 2 of 9 pairs
  /// in a local optimum its re-simulation missed by 6e-2, against 3e-5 with all pairs).
  int all_pairs_up_to = 0;
  double pair_margin = 0.1;  ///< lazy pairs' margin, relative to the pair's size (pairSize)
  /// The first round's margin: the pairs the first guess comes this near (relative to pairSize)
  /// are modelled from the start, since the solution strays from the guess.
  double first_round_margin = 0.1;
  /// A plan whose collocation polynomial cuts into a pair it holds no force of deeper than this,
  /// relative to the pair's size, between stage points grazes it (planGrazes).
  double graze_depth = 1e-6;
  /// Re-simulate the optimal controls finely with every pair in reach modelled and report the
  /// end state's deviation.
  bool verify = false;
  /// The re-simulation's discretisation, raised to at least the solve's stages and twice its
  /// elements per interval; its budget is what the solve left of the total.
  DiscretizationOptions verification;
  /// Warm start from this outcome of an earlier solve when warmStartMismatch allows it (falling
  /// back to the push plan if the warm solve fails); nullptr: cold. Not owned.
  const SceneOutcome* previous = nullptr;
  /// A solution of this task on a coarser grid (the accuracy ladder's rung before): the solve
  /// models its pairs and starts from its plan mapped onto this grid (refinedTrajectory), its
  /// active set first (OcpSolver::solveFromPlan), falling back to the push plan. Not owned.
  const SceneOutcome* refine = nullptr;
  /// Pairs whose gaps are kept along whole elements of these intervals from the first round.
  std::vector<PairInterval> held_grazes;
  /// Solves that hold the plan's new grazes (gap guards) before the answer, at most (in every
  /// scene). A cut held only at its deepest point moved beside it, about 4x shallower a round
  /// (a pusher sliding over the kinks between a T's spheres: from 5e-4 to 1.2e-6 of depth in 4
  /// rounds); held beside it too, cluttered seed 7 needs 3 rounds instead of 4.
  int max_graze_rounds = 6;
  const SolveMonitor* monitor = nullptr;  ///< progress and cancel of the solve; not owned
};

/// What a replan (`outcome`, of `task` on `ocp`'s grid) holds of the plan before, so that its
/// NLP can be the same: the grazes that plan held and their deepest points. Where the replan
/// starts later on the same grid (the closed loop's, `done` intervals on: intervalsDone), those
/// in the intervals still to come, moved to the replan's intervals and elements.
void holdWhatThePlanBeforeHeld(const SceneOutcome& previous, const SceneTask& task,
                               const OcpOptions& ocp, SceneOutcome& outcome);

/// The planning entry point of a scene task: validateTask, infeasibility, decidePairs, the first
/// guess of the pairs in reach (the push plan, or for a robot its inverse kinematics:
/// planRobotGuess; deterministic, so the same task gives the same plan on every machine), then
/// rounds of movingPart, buildOcp and OcpSolver over the modelled pairs (lazy pairs: the first
/// round from the guess, each later one from the round before), the trajectory of the full scene,
/// the targets judged (a success that misses a weighted target by more than targetTolerance is
/// kTargetNotReached) and, on request, the verification.
SceneOutcome solveSceneTask(const SceneTask& task, const TaskLimits& limits,
                            const SceneSolveOptions& options);

/// Ipopt iterations per relaxed NLP of a verification step's homotopy (SimulationOptions).
constexpr int kVerificationNlpIterations = 100;

/// The grid a plan is verified on: the configured one, but at least the solve's stages and twice
/// its elements; with the solve's linear solver, within the budget left (none when the solve used
/// it all); a step's homotopy stops each relaxed NLP after kVerificationNlpIterations (the step
/// is split instead).
SimulationOptions verificationOptions(const DiscretizationOptions& configured,
                                      const OcpOptions& solve, double remaining_budget);

/// The smallest gap of `pairs` over the states at the trajectory's element boundaries.
double smallestBoundaryGap(const Scene& scene, const std::vector<ContactPair>& pairs,
                           const Trajectory& trajectory);

/// The simulation entry point: the scene moved by given controls (per step, the full scene's
/// control vector; one value for all steps, or num_intervals values). Physics only: workspace
/// bounds (OCP constraints) are neither enforced nor used to prune, and each body's reach comes
/// from the commands it gets, not from its speed bound. The task's num_intervals is the number
/// of steps.
SceneOutcome simulateSceneTask(SceneTask task, const std::vector<Eigen::VectorXd>& controls,
                               const TaskLimits& limits, const SimulationOptions& options);

}  // namespace fesd
