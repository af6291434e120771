// The accuracy ladder: what accuracy costs in time, answered per request.
#include "fesd_trajopt/planning/accuracy_ladder.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fesd_trajopt/planning/scene_solver.h"

namespace fesd {

std::vector<std::pair<int, int>> accuracyRungs(int stages, int elements, const TaskLimits& limits) {
  std::vector<std::pair<int, int>> rungs{{stages, elements}};
  while (stages < limits.max_stages) rungs.emplace_back(++stages, elements);
  while (elements < limits.max_elements) rungs.emplace_back(stages, ++elements);
  return rungs;
}

bool solvedItsNlp(SolveStatus status) {
  return status == SolveStatus::kSuccess || status == SolveStatus::kTargetNotReached;
}

double AccuracyLadder::remainingBudget() const {
  return std::max(0.0, budget_ - stopwatch_.wallSeconds());
}

bool AccuracyLadder::record(const AccuracyRung& rung) {
  rungs_.push_back(rung);
  // A plan that misses an unreachable target is still a plan whose accuracy counts.
  const bool solved = solvedItsNlp(rung.status);
  const double error = std::isnan(rung.verification_error) ? std::numeric_limits<double>::infinity()
                                                           : rung.verification_error;
  met_ = solved && error <= target_;
  cancelled_ = rung.status == SolveStatus::kCancelled;
  out_of_time_ = rung.status == SolveStatus::kTimeout || remainingBudget() <= 0.0;
  const bool best =
      rungs_.size() == 1 || (solved && (!solvedItsNlp(best_status_) || error < best_error_));
  if (best) {
    best_error_ = error;
    best_status_ = rung.status;
  }
  return best;
}

SolveStatus AccuracyLadder::finalStatus(SolveStatus best) const {
  if (cancelled_) return SolveStatus::kCancelled;
  // A solution that is not accurate enough says why it is no SUCCESS; a failure keeps its own.
  if (!met_ && solvedItsNlp(best)) {
    return out_of_time_ ? SolveStatus::kTimeout : SolveStatus::kAccuracyNotMet;
  }
  return best;
}

std::string AccuracyLadder::summary() const {
  std::ostringstream message;
  message << "accuracy target " << target_;
  if (met_) {
    message << " met on rung " << rungs_.size() << " (n_s = " << rungs_.back().stages
            << ", N_FE = " << rungs_.back().elements << "): verification error " << best_error_;
  } else if (cancelled_) {
    message << " not met: cancelled on rung " << rungs_.size();
  } else {
    message << " not met: best verification error " << best_error_ << " (of " << rungs_.size()
            << " rung(s), " << (out_of_time_ ? "the wall-time budget spent" : "the ladder ended")
            << ")";
  }
  return message.str();
}

SceneOutcome solveToAccuracy(const SceneTask& task, const TaskLimits& limits,
                             SceneSolveOptions options, double target_accuracy) {
  options.verify = true;
  const SceneOutcome* previous = options.previous;
  if (previous && solvedItsNlp(previous->status) && previous->verified) {
    startOnPreviousRung(previous->structure, options.ocp.discretization);
  }
  return climbAccuracyLadder<SceneOutcome>(
      options, limits, target_accuracy,
      [&](const SceneSolveOptions& rung) {
        SceneOutcome outcome = solveSceneTask(task, limits, rung);
        if (!outcome.verified) outcome.verification_error = std::numeric_limits<double>::infinity();
        return outcome;
      },
      [](const SceneOutcome& outcome) { return !outcome.solved(); });
}

}  // namespace fesd
