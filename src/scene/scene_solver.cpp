#include "fesd_trajopt/scene/scene_solver.h"

#include <algorithm>
#include <stdexcept>

#include "fesd_trajopt/scene/moving_part.h"
#include "fesd_trajopt/scene/push_plan.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {
namespace {

/// Validation, infeasibility and the pair decisions: what both entry points do before solving.
/// False when the task is not to be solved.
bool prepare(const SceneTask& task, const TaskLimits& limits, bool check_goals,
             SceneOutcome& outcome) {
  outcome.invalid = validateTask(task, limits);
  if (!outcome.invalid.empty()) return false;
  if (check_goals) outcome.infeasible = infeasibility(task);
  if (!outcome.infeasible.empty()) return false;
  outcome.decisions = decidePairs(task);
  return true;
}

MovingPart movingPartOf(const SceneTask& task, SceneOutcome& outcome) {
  MovingPart part = movingPart(task, outcome.decisions);
  outcome.moving_bodies = part.bodies;
  return part;
}

}  // namespace

SceneOutcome solveSceneTask(const SceneTask& task, const TaskLimits& limits,
                            const SceneSolveOptions& options) {
  Stopwatch stopwatch;
  SceneOutcome outcome;
  if (!prepare(task, limits, true, outcome)) return outcome;
  if (!options.prune_pairs) {
    for (PairDecision& decision : outcome.decisions) decision.modelled = true;
  }
  const MovingPart part = movingPartOf(task, outcome);
  const OcpDefinition ocp = buildOcp(part.task, part.modelled);
  OcpSolver solver(ocp, options.ocp);
  const OcpSolution solution = solver.solve(planPushes(part.task, part.modelled).guess);
  outcome.status = solution.status;
  outcome.message = solution.message;
  outcome.start = solution.start;
  outcome.trajectory = fullSceneTrajectory(task, part, solution.trajectory);
  outcome.report = solution.report;
  const NlpAssembly& nlp = solver.discretization().nlp();
  outcome.sizes = {nlp.numVariables(), nlp.numConstraints(), nlp.numComplementarities()};
  if (options.verify) {
    SimulationOptions fine;
    fine.discretization = options.verification;
    // 0 when the solve used it all: the re-simulation times out and its error is infinite.
    fine.wall_time_budget =
        std::max(0.0, options.ocp.homotopy.wall_time_budget - stopwatch.wallSeconds());
    outcome.verified = true;
    outcome.verification_error = resimulationError(ocp, solution, fine);
  }
  return outcome;
}

SceneOutcome simulateSceneTask(SceneTask task, const std::vector<Eigen::VectorXd>& controls,
                               const TaskLimits& limits, const SimulationOptions& options) {
  const int steps = task.num_intervals;
  SceneOutcome outcome;
  if (controls.size() != 1 && static_cast<int>(controls.size()) != steps) {
    outcome.invalid = "the controls must be one for all steps or one per step";
    return outcome;
  }
  for (const Eigen::VectorXd& u : controls) {
    if (u.size() != task.scene.controlSize() || !u.allFinite()) {
      outcome.invalid = "every control must be finite and of the scene's control size";
      return outcome;
    }
  }
  const int dim = task.scene.dimension();
  for (size_t b = 0; b < task.bodies.size(); ++b) {
    BodyTask& body = task.bodies[b];
    body.workspace_lower.resize(0);
    body.workspace_upper.resize(0);
    body.max_speed = 0.0;
    if (b >= task.scene.bodies().size() || !task.scene.bodies()[b].actuated) continue;
    for (const Eigen::VectorXd& u : controls) {
      const int first = task.scene.controlIndex(static_cast<int>(b));
      body.max_speed = std::max(body.max_speed, u.segment(first, dim).cwiseAbs().maxCoeff());
    }
  }
  if (!prepare(task, limits, false, outcome)) return outcome;
  const MovingPart part = movingPartOf(task, outcome);
  const DiscScene& moving = part.task.scene;
  FesdIntegrator integrator(moving.model(part.modelled), options);
  const SimulationResult result =
      integrator.simulate(moving.initialState(), task.horizon, steps, controls);
  outcome.status = result.status;
  outcome.message = result.message;
  outcome.trajectory = fullSceneTrajectory(task, part, result.trajectory);
  outcome.report = result.totals;
  return outcome;
}

}  // namespace fesd
