// One plan in any units: a scene is solved in units of its own length scale and answered in its
// user's (docs/design.md, "One plan in any units").
#include "fesd_trajopt/planning/length_units.h"

#include <memory>

#include "fesd_trajopt/scene/scene_units.h"

namespace fesd {
namespace {

/// A pair's constraint in lengths: 2 for a pair of spheres (|d|^2 - R^2), 1 for a wall.
double constraintPower(const ContactPair& pair) {
  return pair.kind == ContactPair::Kind::kWall ? 1.0 : 2.0;
}

void scaleRows(Eigen::MatrixXd& values, const std::vector<double>& row_factors) {
  if (values.rows() != static_cast<int>(row_factors.size())) return;
  for (int k = 0; k < values.rows(); ++k) values.row(k) *= row_factors[k];
}

void scaleGrazes(std::vector<Graze>& grazes, double factor) {
  for (Graze& graze : grazes) graze.depth *= factor;
}

void scaleVerification(Verification& verification, double factor) {
  verification.error *= factor;
  for (double& error : verification.interval_errors) error *= factor;
  verification.open_loop_error *= factor;
  scaleTrajectory(verification.open_loop, verification.open_loop_pairs, factor);
  verification.gap *= factor;
  scaleGrazes(verification.grazes, factor);
}

void scalePlannedPushes(SceneOutcome& outcome, double factor) {
  for (PushLeg& leg : outcome.planned_legs) {
    leg.from *= factor;
    leg.to *= factor;
    for (PushAssignment& push : leg.pushes) push.offset *= factor;
    for (Eigen::VectorXd& point : leg.through) point *= factor;
    leg.turn_radius *= factor;
  }
  for (Transit& transit : outcome.planned_transits) {
    for (Eigen::VectorXd& point : transit.path) point *= factor;
  }
}

}  // namespace

void scaleTrajectory(Trajectory& trajectory, const std::vector<ContactPair>& pairs, double factor) {
  std::vector<double> constraint_factors, multiplier_factors;
  for (const ContactPair& pair : pairs) {
    const double power = constraintPower(pair);
    constraint_factors.push_back(std::pow(factor, power));
    multiplier_factors.push_back(std::pow(factor, 2.0 - power));
  }
  for (Eigen::VectorXd& x : trajectory.states) x *= factor;
  for (Eigen::VectorXd& u : trajectory.controls) u *= factor;
  for (ElementValues& element : trajectory.elements) {
    element.stage_states *= factor;
    scaleRows(element.stage_multipliers, multiplier_factors);
    scaleRows(element.stage_constraints, constraint_factors);
    element.lowest_constraints *= factor;
  }
}

void scaleOutcome(SceneOutcome& outcome, double factor) {
  for (PairDecision& decision : outcome.decisions) decision.min_distance *= factor;
  scalePlannedPushes(outcome, factor);
  scaleTrajectory(outcome.trajectory, outcome.modelled, factor);
  outcome.report.objective *= factor * factor;
  for (HomotopyStep& step : outcome.report.history) step.objective *= factor * factor;
  outcome.boundary_gap *= factor;
  scaleVerification(outcome.verification, factor);
  scaleGrazes(outcome.guard_points, factor);
  scaleGrazes(outcome.grazes, factor);
  for (AccuracyRung& rung : outcome.refinements) {
    rung.verification_error *= factor;
    rung.error_before *= factor;
  }
  for (Eigen::RowVectorXd& row : outcome.sensitivities.switch_times) row /= factor;
  for (double& distance : outcome.target_distances) distance *= factor;
  for (double& distance : outcome.joint_target_distances) distance *= factor;
}

SceneOutcome solveInLengthUnits(
    const SceneTask& task, const TaskLimits& limits, SceneSolveOptions options,
    const std::function<SceneOutcome(const SceneTask&, const SceneSolveOptions&)>& solve) {
  SceneOutcome refused;
  refused.invalid = validateTask(task, limits);
  if (refused.invalid.empty()) refused.infeasible = infeasibility(task);
  if (!refused.solved()) return refused;
  const double length = lengthScale(task);
  options.length_scaling = false;
  // The earlier outcomes the solve starts from, in its units (owned here).
  std::unique_ptr<SceneOutcome> previous, refine;
  if (options.previous) {
    previous = std::make_unique<SceneOutcome>(*options.previous);
    scaleOutcome(*previous, 1.0 / length);
    options.previous = previous.get();
  }
  if (options.refine) {
    refine = std::make_unique<SceneOutcome>(*options.refine);
    scaleOutcome(*refine, 1.0 / length);
    options.refine = refine.get();
  }
  // The monitor is told each step's objective in the task's units, as the outcome.
  SolveMonitor monitor;
  if (options.monitor) {
    monitor.cancel = options.monitor->cancel;
    monitor.on_step = [&, told = options.monitor](const HomotopyStep& step) {
      HomotopyStep scaled = step;
      scaled.objective *= length * length;
      if (told->on_step) told->on_step(scaled);
    };
    options.monitor = &monitor;
  }
  SceneOutcome outcome = solve(taskInLengthUnits(task, length), options);
  scaleOutcome(outcome, length);
  outcome.length_scale = length;
  return outcome;
}

}  // namespace fesd
