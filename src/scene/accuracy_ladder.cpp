// solveToAccuracy: what accuracy costs in time, answered per request.
#include <algorithm>
#include <limits>
#include <sstream>
#include <utility>
#include <vector>

#include "fesd_trajopt/scene/scene_solver.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {
namespace {

/// (stages, elements) of each rung: more stages first (the order grows with n_s: 2 n_s - 1 for
/// Radau-IIA, at the same NLP structure per element), then more elements.
std::vector<std::pair<int, int>> ladder(int stages, int elements, const TaskLimits& limits) {
  std::vector<std::pair<int, int>> rungs{{stages, elements}};
  while (stages < limits.max_stages) rungs.emplace_back(++stages, elements);
  while (elements < limits.max_elements) rungs.emplace_back(stages, ++elements);
  return rungs;
}

}  // namespace

SceneOutcome solveToAccuracy(const SceneTask& task, const TaskLimits& limits,
                             SceneSolveOptions options, double target_accuracy) {
  Stopwatch stopwatch;
  const double budget = options.ocp.homotopy.wall_time_budget;
  options.verify = true;
  std::vector<AccuracyRung> rungs;
  SceneOutcome best;
  bool met = false, out_of_time = false, cancelled = false;
  for (const auto& [stages, elements] : ladder(options.ocp.discretization.num_stages,
                                               options.ocp.discretization.num_elements, limits)) {
    Stopwatch rung_time;
    options.ocp.discretization.num_stages = stages;
    options.ocp.discretization.num_elements = elements;
    options.ocp.homotopy.wall_time_budget = std::max(0.0, budget - stopwatch.wallSeconds());
    SceneOutcome outcome = solveSceneTask(task, limits, options);
    if (!outcome.solved()) return outcome;  // refused or infeasible: no rung can change that
    if (!outcome.verified) outcome.verification_error = std::numeric_limits<double>::infinity();
    rungs.push_back(
        {stages, elements, outcome.verification_error, rung_time.wallSeconds(), outcome.status});
    // A plan that misses an unreachable target is still a plan whose accuracy counts.
    const bool success = solvedItsNlp(outcome.status);
    met = success && outcome.verification_error <= target_accuracy;
    cancelled = outcome.status == SolveStatus::kCancelled;
    out_of_time = outcome.status == SolveStatus::kTimeout || stopwatch.wallSeconds() >= budget;
    // Keep the most accurate successful rung (a failed verification's error is infinite).
    if (rungs.size() == 1 || (success && (!solvedItsNlp(best.status) ||
                                          outcome.verification_error < best.verification_error))) {
      best = std::move(outcome);
    }
    if (met || cancelled || out_of_time) break;
  }
  best.refinements = rungs;
  std::ostringstream message;
  message << "accuracy target " << target_accuracy;
  if (met) {
    message << " met on rung " << rungs.size() << " (n_s = " << rungs.back().stages
            << ", N_FE = " << rungs.back().elements << "): verification error "
            << best.verification_error;
  } else if (cancelled) {
    message << " not met: cancelled on rung " << rungs.size();
  } else {
    message << " not met: best verification error " << best.verification_error << " (of "
            << rungs.size() << " rung(s), "
            << (out_of_time ? "the wall-time budget spent" : "the ladder ended") << ")";
  }
  best.message = message.str() + "; " + best.message;
  // A successful rung that is not accurate enough says why it is no SUCCESS; a failed one keeps
  // its own status.
  if (cancelled) {
    best.status = SolveStatus::kCancelled;
  } else if (!met && solvedItsNlp(best.status)) {
    best.status = out_of_time ? SolveStatus::kTimeout : SolveStatus::kAccuracyNotMet;
  }
  return best;
}

}  // namespace fesd
