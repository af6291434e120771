// A plan executed with feedback: replans from the state reached, warm from the rest of the plan.
#include "fesd_trajopt/planning/closed_loop.h"

#include <algorithm>
#include <memory>

#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {

namespace {

void widenWorkspacesToStarts(SceneTask& task) {
  for (size_t b = 0; b < task.bodies.size() && b < task.scene.bodies().size(); ++b) {
    BodyTask& body = task.bodies[b];
    const Eigen::VectorXd& start = task.scene.bodies()[b].position;
    if (body.workspace_lower.size() == start.size()) {
      body.workspace_lower = body.workspace_lower.cwiseMin(start);
    }
    if (body.workspace_upper.size() == start.size()) {
      body.workspace_upper = body.workspace_upper.cwiseMax(start);
    }
  }
}

/// An outcome's status, and what it says: one refused before its solve is SOLVER_ERROR (an
/// invalid request) or INFEASIBLE (goals no motion can meet in the time it has).
SolveStatus statusOf(const SceneOutcome& outcome) {
  if (!outcome.invalid.empty()) return SolveStatus::kSolverError;
  return outcome.infeasible.empty() ? outcome.status : SolveStatus::kInfeasible;
}

std::string messageOf(const SceneOutcome& outcome) {
  if (!outcome.invalid.empty()) return outcome.invalid;
  return outcome.infeasible.empty() ? outcome.message : "infeasible: " + outcome.infeasible;
}

}  // namespace

ClosedLoopRun executeWithFeedback(const SceneTask& task, const TaskLimits& limits,
                                  const ClosedLoopOptions& options) {
  ClosedLoopRun run;
  Stopwatch first_time;
  if (options.first_plan != nullptr) {
    run.first = *options.first_plan;
  } else {
    run.first = options.first_accuracy > 0.0
                    ? solveToAccuracy(task, limits, options.first, options.first_accuracy)
                    : solveSceneTask(task, limits, options.first);
  }
  run.first_seconds = first_time.wallSeconds();
  // A plan less accurate than asked is still the best there is to execute.
  if (!run.first.solved() || !solvedItsNlp(run.first.status)) {
    run.status = statusOf(run.first);
    run.message = "the first plan: " + messageOf(run.first);
    return run;
  }
  const double interval = task.horizon / task.num_intervals;
  auto plan = std::make_shared<SceneOutcome>(run.first);
  int used = 0;  // the plan's intervals executed so far
  SceneTask now = task;
  Eigen::VectorXd state = task.scene.initialState();
  for (int done = 0; done < task.num_intervals;) {
    const int steps = std::min(options.replan_every, task.num_intervals - done);
    // The plant: the next intervals of the current plan from where the execution got to.
    SceneTask stretch = now;
    stretch.horizon = steps * interval;
    stretch.num_intervals = steps;
    const std::vector<Eigen::VectorXd> controls(plan->trajectory.controls.begin() + used,
                                                plan->trajectory.controls.begin() + used + steps);
    const SceneOutcome executed = simulateSceneTask(stretch, controls, limits, options.plant);
    if (!executed.solved() || executed.status != SolveStatus::kSuccess) {
      run.status = executed.solved() ? executed.status : SolveStatus::kSolverError;
      run.message = "the plant's simulation after " + std::to_string(done) +
                    " interval(s): " + (executed.solved() ? executed.message : executed.invalid);
      return run;
    }
    Trajectory piece = executed.trajectory;
    for (double& t : piece.times) t += done * interval;
    for (ElementValues& element : piece.elements) {
      element.start_time += done * interval;
      element.interval += done;
    }
    if (run.executed.elements.empty()) {
      run.executed = piece;
    } else {
      run.executed.append(piece);
    }
    state = executed.trajectory.finalState();
    done += steps;
    used += steps;
    if (done == task.num_intervals) break;
    // A replan over the rest of the horizon from the state reached; a body the plant carried past
    // a workspace bound replans from there, the bound widened to its start.
    now.scene.setInitialState(state);
    widenWorkspacesToStarts(now);
    now.horizon = (task.num_intervals - done) * interval;
    now.num_intervals = task.num_intervals - done;
    SceneSolveOptions replan = options.replan;
    replan.previous = plan.get();
    // On the grid of the plan before (of its intervals still to come), so that it fits.
    startOnPreviousRung(plan->structure, now.num_intervals, now.horizon, replan.ocp.discretization);
    Stopwatch replan_time;
    auto next = std::make_shared<SceneOutcome>(solveSceneTask(now, limits, replan));
    Replan record;
    record.after_intervals = done;
    record.seconds = replan_time.wallSeconds();
    record.status = statusOf(*next);
    record.iterations = next->report.iterations;
    record.warm_started = next->warm_started;
    record.pair_rounds = next->pair_rounds;
    record.history = next->report.history;
    record.message = messageOf(*next);
    run.replans.push_back(record);
    run.replan_seconds += record.seconds;
    // A replan that did not solve its NLP leaves the plan before in charge.
    if (next->solved() && solvedItsNlp(next->status)) {
      plan = next;
      used = 0;
    }
  }
  run.end = state;
  run.status = SolveStatus::kSuccess;
  run.message = "executed with " + std::to_string(run.replans.size()) + " replan(s)";
  return run;
}

}  // namespace fesd
