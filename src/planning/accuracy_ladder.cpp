// The accuracy ladder: what accuracy costs in time, answered per request, each rung refining
// what the verification blames in the plan the rung before found.
#include "fesd_trajopt/planning/accuracy_ladder.h"

#include "fesd_trajopt/planning/length_units.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <tuple>

namespace fesd {
namespace {

/// The control intervals as "3, 7-9".
std::string intervalList(const std::vector<int>& intervals) {
  std::ostringstream text;
  for (size_t i = 0; i < intervals.size();) {
    size_t j = i;
    while (j + 1 < intervals.size() && intervals[j + 1] == intervals[j] + 1) ++j;
    text << (i ? ", " : "") << intervals[i];
    if (j > i) text << "-" << intervals[j];
    i = j + 1;
  }
  return text.str();
}

/// Per control interval, whether a switch in it is beyond what its element boundaries resolve:
/// an unresolved switch of the plan (inside an element), or a contact of the re-simulation that
/// the plan does not hold (a graze). A resolved switch keeps the full order; these do not.
std::vector<bool> unresolvedIntervals(const SceneOutcome& outcome, int intervals) {
  std::vector<bool> unresolved(intervals, false);
  for (const UnresolvedSwitch& inside : outcome.trajectory.unresolved_switches) {
    unresolved[inside.interval] = true;
  }
  for (const Graze& graze : outcome.verification.grazes) unresolved[graze.interval] = true;
  return unresolved;
}

}  // namespace

bool solvedItsNlp(SolveStatus status) {
  return status == SolveStatus::kSuccess || status == SolveStatus::kTargetNotReached ||
         status == SolveStatus::kAccuracyNotMet;
}

double AccuracyLadder::remainingBudget() const {
  return std::max(0.0, budget_ - stopwatch_.wallSeconds());
}

bool AccuracyLadder::meets(const AccuracyRung& rung) const {
  return solvedItsNlp(rung.status) && rung.grazes == 0 && rung.verification_error <= target_;
}

bool AccuracyLadder::record(const AccuracyRung& rung) {
  rungs_.push_back(rung);
  met_ = meets(rung);
  cancelled_ = rung.status == SolveStatus::kCancelled;
  out_of_time_ = rung.status == SolveStatus::kTimeout || remainingBudget() <= 0.0;
  const auto error = [](const AccuracyRung& r) {
    return std::isnan(r.verification_error) ? std::numeric_limits<double>::infinity()
                                            : r.verification_error;
  };
  // Better: meeting the target, then solving its NLP, then a smaller error, then fewer grazes.
  const auto rank = [&](const AccuracyRung& r) {
    return std::make_tuple(!meets(r), !solvedItsNlp(r.status), error(r), r.grazes);
  };
  const bool best = best_ < 0 || rank(rung) < rank(rungs_[best_]);
  if (best) best_ = static_cast<int>(rungs_.size()) - 1;
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
  message << "accuracy target " << length_unit_ * target_;
  const AccuracyRung& best = rungs_[best_];
  const auto [fewest, most] =
      std::minmax_element(best.interval_elements.begin(), best.interval_elements.end());
  std::ostringstream grid;
  grid << "n_s = " << best.stages << ", N_FE = " << *fewest;
  if (*most != *fewest) grid << "-" << *most;
  if (met_) {
    message << " met on rung " << rungs_.size() << " (" << grid.str() << "): verification error "
            << length_unit_ * best.verification_error;
  } else if (cancelled_) {
    message << " not met: cancelled on rung " << rungs_.size();
  } else {
    message << " not met: best verification error " << length_unit_ * best.verification_error;
    if (best.grazes > 0) message << " with " << best.grazes << " graze(s) left";
    message << " (rung " << best_ + 1 << " of " << rungs_.size() << ", "
            << (out_of_time_ ? "the wall-time budget spent" : "the ladder ended") << ")";
  }
  return message.str();
}

RungChange nextRung(const SceneTask& task, const SceneOutcome& outcome, int stages,
                    const std::vector<int>& interval_elements, const TaskLimits& limits,
                    double target_accuracy, double graze_depth) {
  RungChange next;
  next.stages = stages;
  next.interval_elements = interval_elements;
  next.held_grazes = outcome.held_grazes;
  const int intervals = static_cast<int>(interval_elements.size());
  const Verification& verification = outcome.verification;
  std::ostringstream change, reason;
  reason.precision(3);
  // Grazes: cuts of the plan into a body between stage points, held from now on.
  std::vector<int> grazed;
  for (const Graze& graze : verification.grazes) {
    if (graze.depth >= -graze_depth * task.scene.pairSize(graze.pair)) continue;
    const PairInterval held{graze.pair, graze.interval};
    if (std::find(next.held_grazes.begin(), next.held_grazes.end(), held) !=
        next.held_grazes.end()) {
      continue;
    }
    next.held_grazes.push_back(held);
    grazed.push_back(graze.interval);
  }
  if (!grazed.empty()) {
    std::sort(grazed.begin(), grazed.end());
    grazed.erase(std::unique(grazed.begin(), grazed.end()), grazed.end());
    change << "grazes held in intervals " << intervalList(grazed);
    reason << "the plan cuts into a body between stage points";
    next.refined_intervals = grazed;
  }
  // The intervals whose error exceeds the target: more elements where a switch is unresolved,
  // a stage more where the error is smooth (resolved switches keep the order), then elements.
  std::vector<int> unresolved, smooth;
  double blamed_error = 0.0;
  const std::vector<bool> inside = unresolvedIntervals(outcome, intervals);
  for (int k = 0; k < intervals && k < static_cast<int>(verification.interval_errors.size()); ++k) {
    if (!(verification.interval_errors[k] > target_accuracy)) continue;
    blamed_error = std::max(blamed_error, verification.interval_errors[k]);
    (inside[k] ? unresolved : smooth).push_back(k);
  }
  const bool failed = verification.status != SolveStatus::kSuccess;
  const auto refine_elements = [&](const std::vector<int>& blamed) {
    std::vector<int> refined;
    for (int k : blamed) {
      const int more = std::min(2 * next.interval_elements[k], limits.max_elements);
      if (more == next.interval_elements[k]) continue;
      next.interval_elements[k] = more;
      refined.push_back(k);
    }
    return refined;
  };
  const std::string also = grazed.empty() ? "" : "; ";
  std::vector<int> refined = refine_elements(unresolved);
  std::string refinement;
  if (!refined.empty()) {
    refinement = "more elements in intervals " + intervalList(refined);
    reason << also << "error up to " << task.scene.userLength(blamed_error)
           << " at switches inside elements";
  }
  if ((!smooth.empty() || failed) && stages < limits.max_stages) {
    next.stages = stages + 1;
    refinement += (refinement.empty() ? "" : "; ") + std::string("n_s ") + std::to_string(stages) +
                  " -> " + std::to_string(stages + 1);
    if (failed) {
      reason << also << "the verification failed";
    } else {
      reason << (refined.empty() ? also : std::string("; ")) << "error up to "
             << task.scene.userLength(blamed_error) << " in smooth intervals "
             << intervalList(smooth);
    }
    refined.insert(refined.end(), smooth.begin(), smooth.end());
  } else if (!smooth.empty()) {
    const std::vector<int> more = refine_elements(smooth);
    if (!more.empty()) {
      refinement += (refinement.empty() ? "" : "; ") + std::string("more elements in intervals ") +
                    intervalList(more);
      reason << (refined.empty() ? also : std::string("; ")) << "error up to "
             << task.scene.userLength(blamed_error) << " in smooth intervals at n_s = " << stages;
      refined.insert(refined.end(), more.begin(), more.end());
    }
  }
  if (!refinement.empty()) change << (grazed.empty() ? "" : "; ") << refinement;
  next.refined_intervals.insert(next.refined_intervals.end(), refined.begin(), refined.end());
  std::sort(next.refined_intervals.begin(), next.refined_intervals.end());
  next.refined_intervals.erase(
      std::unique(next.refined_intervals.begin(), next.refined_intervals.end()),
      next.refined_intervals.end());
  next.none = grazed.empty() && refinement.empty();
  next.change = change.str();
  next.reason = reason.str();
  next.error_before = blamed_error > 0.0 ? blamed_error : verification.error;
  return next;
}

SceneOutcome solveToAccuracy(const SceneTask& task, const TaskLimits& limits,
                             SceneSolveOptions options, double target_accuracy) {
  if (options.length_scaling) {
    return solveInLengthUnits(task, options,
                              [&](const SceneTask& scaled, const SceneSolveOptions& inner) {
                                return solveToAccuracy(scaled, limits, inner, target_accuracy);
                              });
  }
  options.verify = true;
  const SceneOutcome* previous = options.previous;
  DiscretizationOptions& grid = options.ocp.discretization;
  if (previous && solvedItsNlp(previous->status) && previous->verified) {
    startOnPreviousRung(previous->structure, task.num_intervals, task.horizon, grid);
  }
  if (grid.interval_elements.empty()) {
    grid.interval_elements.assign(task.num_intervals, grid.num_elements);
  }
  AccuracyLadder ladder(target_accuracy, options.ocp.homotopy.wall_time_budget,
                        task.scene.length_unit);
  SceneOutcome best, last;
  RungChange change;
  for (int rung = 0;; ++rung) {
    Stopwatch rung_time;
    options.ocp.homotopy.wall_time_budget = ladder.remainingBudget();
    SceneOutcome outcome = solveSceneTask(task, limits, options);
    if (!outcome.solved()) return outcome;
    AccuracyRung record;
    record.stages = grid.num_stages;
    record.interval_elements = grid.interval_elements;
    record.change = change.change;
    record.reason = change.reason;
    record.refined_intervals = change.refined_intervals;
    record.error_before =
        rung == 0 ? std::numeric_limits<double>::quiet_NaN() : change.error_before;
    record.verification_error = outcome.verified && solvedItsNlp(outcome.status)
                                    ? outcome.verification.error
                                    : std::numeric_limits<double>::infinity();
    record.grazes = static_cast<int>(outcome.grazes.size());
    record.from_previous_plan = outcome.refined_plan;
    if (rung > 0 && !outcome.refined_plan) {
      record.change += (record.change.empty() ? "" : "; ") + std::string("cold path");
    }
    record.wall_seconds = rung_time.wallSeconds();
    record.status = outcome.status;
    const bool is_best = ladder.record(record);
    if (ladder.finished()) {
      if (is_best) best = std::move(outcome);
      break;
    }
    change = nextRung(task, outcome, grid.num_stages, grid.interval_elements, limits,
                      target_accuracy, options.graze_depth);
    if (change.none) {
      ladder.end();
      if (is_best) best = std::move(outcome);
      break;
    }
    // The next rung refines the plan this one found when it is one (else the best so far).
    if (solvedItsNlp(outcome.status)) {
      last = outcome;
    } else if (rung == 0) {
      last = SceneOutcome();
    }
    if (is_best) best = std::move(outcome);
    grid.num_stages = change.stages;
    grid.interval_elements = change.interval_elements;
    options.held_grazes = change.held_grazes;
    options.refine = last.trajectory.elements.empty() ? nullptr : &last;
    options.previous = nullptr;  // the first rung used it
  }
  best.refinements = ladder.rungs();
  best.status = ladder.finalStatus(best.status);
  best.message = ladder.summary() + "; " + best.message;
  return best;
}

}  // namespace fesd
