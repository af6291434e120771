#pragma once

#include <algorithm>
#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// The sizes of the NLP a scene task became.
struct NlpSizes {
  int variables = 0, constraints = 0, complementarities = 0;
};

/// A scene task solved or simulated, in the full scene's terms. A task that is refused
/// (`invalid`) or cannot be met (`infeasible`) is never solved: status and trajectory stay
/// at their defaults.
struct SceneOutcome {
  std::string invalid;     ///< why validateTask refused the task; "" when valid
  std::string infeasible;  ///< why infeasibility() says the goals cannot be met; "" otherwise
  std::vector<PairDecision> decisions;  ///< every pair of the scene: modelled or why not
  std::vector<int> moving_bodies;       ///< the bodies with states (MovingPart::bodies)
  SolveStatus status = SolveStatus::kSolverError;
  std::string message;
  OcpStart start = OcpStart::kConstant;  ///< the solve's start (not for simulations)
  Trajectory trajectory;                 ///< of the full scene: frozen bodies at their start
  MpccReport report;                     ///< the solve's, or a simulation's totals
  NlpSizes sizes;                        ///< the solve's NLP (a simulation's step NLP: none)
  bool verified = false;
  /// Distance of the re-simulated terminal state from the solution's (resimulationError).
  double verification_error = std::numeric_limits<double>::quiet_NaN();

  bool solved() const { return invalid.empty() && infeasible.empty(); }
  int modelledPairs() const {
    return static_cast<int>(std::count_if(decisions.begin(), decisions.end(),
                                          [](const PairDecision& d) { return d.modelled; }));
  }
};

struct SceneSolveOptions {
  OcpOptions ocp;           ///< discretisation and homotopy (its wall-time budget covers all)
  bool prune_pairs = true;  ///< model only the pairs that can touch (decidePairs); else all
  bool verify = false;      ///< re-simulate the optimal controls finely (resimulationError)
  /// The re-simulation's discretisation; its budget is what the solve left of the total.
  DiscretizationOptions verification;
};

/// The planning entry point of a scene task: validateTask, infeasibility, decidePairs,
/// movingPart, buildOcp, then OcpSolver from the push plan (a deterministic guess: the same task
/// gives the same plan on every machine), the trajectory of the full scene and, on request,
/// the verification.
SceneOutcome solveSceneTask(const SceneTask& task, const TaskLimits& limits,
                            const SceneSolveOptions& options);

/// The simulation entry point: the scene moved by given controls (per step, the full scene's
/// control vector; one value for all steps, or num_intervals values). Physics only: workspace
/// bounds (OCP constraints) are neither enforced nor used to prune, and each body's reach comes
/// from the commands it gets, not from its speed bound. The task's num_intervals is the number
/// of steps.
SceneOutcome simulateSceneTask(SceneTask task, const std::vector<Eigen::VectorXd>& controls,
                               const TaskLimits& limits, const SimulationOptions& options);

}  // namespace fesd
