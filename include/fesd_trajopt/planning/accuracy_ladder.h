#pragma once

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "fesd_trajopt/scene/scene_task.h"
#include "fesd_trajopt/solver/mpcc_solver.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {

/// One rung of an accuracy ladder: a solve on this discretisation and its verification.
struct AccuracyRung {
  int stages = 0, elements = 0;
  double verification_error = std::numeric_limits<double>::infinity();
  double wall_seconds = 0.0;
  SolveStatus status = SolveStatus::kSolverError;
};

/// (stages, elements) of each rung from a first discretisation: more stages first (the order
/// grows with n_s: 2 n_s - 1 for Radau-IIA, at the same NLP structure per element), then more
/// elements per interval, up to the limits.
std::vector<std::pair<int, int>> accuracyRungs(int stages, int elements, const TaskLimits& limits);

/// Whether an outcome of this status is a solution of its NLP: a success, or one whose only
/// shortfall is a target it did not reach.
bool solvedItsNlp(SolveStatus status);

/// The bookkeeping of a ladder, whatever kind of task climbs it: which rung is the best, when to
/// stop, and the answer's status and message.
class AccuracyLadder {
 public:
  AccuracyLadder(double target_accuracy, double budget)
      : target_(target_accuracy), budget_(budget) {}

  double remainingBudget() const;
  /// Records a rung (error infinite when unverified or failed); true when its outcome is the
  /// best so far (the most accurate solution of its NLP, else the first rung).
  bool record(const AccuracyRung& rung);
  bool finished() const { return met_ || cancelled_ || out_of_time_; }
  const std::vector<AccuracyRung>& rungs() const { return rungs_; }
  /// The best rung's status once the ladder ended: kAccuracyNotMet (or kTimeout) for a
  /// solution that is not accurate enough, kCancelled when cancelled, else its own.
  SolveStatus finalStatus(SolveStatus best) const;
  /// What the ladder found, to put before the best rung's own message.
  std::string summary() const;

 private:
  double target_, budget_;
  Stopwatch stopwatch_;
  std::vector<AccuracyRung> rungs_;
  double best_error_ = std::numeric_limits<double>::infinity();
  SolveStatus best_status_ = SolveStatus::kSolverError;
  bool met_ = false, cancelled_ = false, out_of_time_ = false;
};

/// The accuracy ladder: `solve(options)` (an outcome with status, message, verification_error
/// and refinements) on `options`' discretisation, then on each further rung of accuracyRungs,
/// each within what is left of the budget, until a rung's verification error is at most
/// target_accuracy (the best rung keeps its status), the budget is spent (kTimeout) or the
/// ladder ends (kAccuracyNotMet). `refused(outcome)`: a task no rung can change (stop there).
template <class Outcome, class Options, class Solve, class Refused>
Outcome climbAccuracyLadder(Options options, const TaskLimits& limits, double target_accuracy,
                            Solve solve, Refused refused) {
  AccuracyLadder ladder(target_accuracy, options.ocp.homotopy.wall_time_budget);
  Outcome best;
  for (const auto& [stages, elements] :
       accuracyRungs(options.ocp.discretization.num_stages, options.ocp.discretization.num_elements,
                     limits)) {
    Stopwatch rung_time;
    options.ocp.discretization.num_stages = stages;
    options.ocp.discretization.num_elements = elements;
    options.ocp.homotopy.wall_time_budget = ladder.remainingBudget();
    Outcome outcome = solve(options);
    if (refused(outcome)) return outcome;
    if (ladder.record({stages, elements, outcome.verification_error, rung_time.wallSeconds(),
                       outcome.status})) {
      best = std::move(outcome);
    }
    if (ladder.finished()) break;
  }
  best.refinements = ladder.rungs();
  best.status = ladder.finalStatus(best.status);
  best.message = ladder.summary() + "; " + best.message;
  return best;
}

}  // namespace fesd
