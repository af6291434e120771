#pragma once

#include <limits>
#include <string>
#include <vector>

#include "fesd_trajopt/planning/accuracy_rung.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {

/// The bookkeeping of a ladder: which rung is the best, when to stop, and the answer's status
/// and message. A rung meets the target when it solved its NLP, its verification error is at
/// most the target and its plan cuts into no body between stage points. Errors and the target
/// are in the solve's length units; the summary prints them times `length_unit` (the user's).
class AccuracyLadder {
 public:
  AccuracyLadder(double target_accuracy, double budget, double length_unit = 1.0)
      : target_(target_accuracy), budget_(budget), length_unit_(length_unit) {}

  double remainingBudget() const;
  /// Records a rung (error infinite when unverified or failed); true when its outcome is the
  /// best so far (a rung that meets the target, else the most accurate solution of its NLP, else
  /// the first rung).
  bool record(const AccuracyRung& rung);
  /// No further rung: the target met, cancelled, out of time, or `ended` (nothing left to refine).
  bool finished() const { return met_ || cancelled_ || out_of_time_ || ended_; }
  void end() { ended_ = true; }
  const std::vector<AccuracyRung>& rungs() const { return rungs_; }
  /// The best rung's status once the ladder ended: kAccuracyNotMet (or kTimeout) for a
  /// solution that is not accurate enough, kCancelled when cancelled, else its own.
  SolveStatus finalStatus(SolveStatus best) const;
  /// What the ladder found, to put before the best rung's own message.
  std::string summary() const;

 private:
  bool meets(const AccuracyRung& rung) const;

  double target_, budget_, length_unit_;
  Stopwatch stopwatch_;
  std::vector<AccuracyRung> rungs_;
  int best_ = -1;
  bool met_ = false, cancelled_ = false, out_of_time_ = false, ended_ = false;
};

/// The next rung of a plan that missed the target: its discretisation and held grazes, and what
/// changed and why (AccuracyRung's change, reason, refined_intervals, error_before).
struct RungChange {
  int stages = 0;
  std::vector<int> interval_elements;
  std::vector<PairInterval> held_grazes;  ///< the previous rung's and the new ones
  std::string change, reason;
  std::vector<int> refined_intervals;
  double error_before = std::numeric_limits<double>::quiet_NaN();
  bool none = true;  ///< nothing left to refine within the limits
};

/// What the verification blames and how the next rung refines it, from the plan it has:
/// its grazes are held (gap guards along the elements of their intervals); intervals whose
/// error exceeds the target and that hold a switch, an unresolved switch or a contact of the
/// re-simulation get more elements (twice as many, up to limits.max_elements); if only smooth
/// intervals are blamed, one more stage everywhere (the order grows with n_s: 2 n_s - 1), then
/// more elements in them. `grid`: the rung's stages and elements per interval.
RungChange nextRung(const SceneTask& task, const SceneOutcome& outcome, int stages,
                    const std::vector<int>& interval_elements, const TaskLimits& limits,
                    double target_accuracy, double graze_depth);

/// The accuracy ladder of a scene task: solved and verified on options' discretisation, then
/// while the verification error exceeds target_accuracy or the plan grazes a body, refined where
/// nextRung blames it, each rung starting from the plan the one before it found (mapped onto the
/// finer grid; the cold path when that fails), within the budget. Returns the rung that met the
/// target, else the most accurate solution (or a failed first rung), with every rung in
/// `refinements`. A warm start (options.previous, a verified solution on a finer rung of this
/// ladder) starts the ladder on that rung. target_accuracy is in units of the task's length scale
/// (1e-2: 1 % of it) unless options.length_scaling is off (then in the task's units).
SceneOutcome solveToAccuracy(const SceneTask& task, const TaskLimits& limits,
                             SceneSolveOptions options, double target_accuracy);

}  // namespace fesd
