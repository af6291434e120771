// One plan in any units: a scene is solved in units of its own length scale and answered in its
// user's (docs/design.md, "One plan in any units").
#include "fesd_trajopt/planning/length_units.h"

#include <cmath>
#include <memory>
#include <stdexcept>

namespace fesd {
namespace {

/// A pair's constraint in lengths: 2 for a pair of spheres (|d|^2 - R^2), 1 for a wall.
double constraintPower(const ContactPair& pair) {
  return pair.kind == ContactPair::Kind::kWall ? 1.0 : 2.0;
}

void scaleRows(Eigen::MatrixXd& values, const Eigen::VectorXd& row_factors) {
  if (values.size() == 0) return;
  if (values.rows() != row_factors.size()) {
    throw std::logic_error("scaleTrajectory: the multipliers' rows are not the pairs given");
  }
  values = row_factors.asDiagonal() * values;
}

/// The units raised to `power` (1: to the user's, -1: to the solve's).
SolveUnits raised(const SolveUnits& units, double power) {
  return {std::pow(units.length, power), units.state.array().pow(power).matrix(),
          units.control.array().pow(power).matrix()};
}

void scaleGrazes(std::vector<Graze>& grazes, double factor) {
  for (Graze& graze : grazes) graze.depth *= factor;
}

/// With `units` raised already. Errors and gaps are lengths (a state's norm in the solve's
/// metric, which counts a revolute joint's motion as an arc at the robot's reach).
void scaleVerification(Verification& verification, const SolveUnits& units) {
  const double length = units.length;
  verification.error *= length;
  for (double& error : verification.interval_errors) error *= length;
  verification.open_loop_error *= length;
  scaleTrajectory(verification.open_loop, verification.open_loop_pairs, units);
  verification.gap *= length;
  scaleGrazes(verification.grazes, length);
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

/// d x / d (x0, u_0, .., u_{N-1}) and d t / d (x0, u...) in other units: rows as states, columns
/// over their coordinates' units.
void scaleSensitivities(SimulationSensitivities& sensitivities, const SolveUnits& units) {
  const auto columns = [&](int count) {
    Eigen::VectorXd scale(count);
    const int nx = units.state.size(), nu = units.control.size();
    scale.head(nx) = units.state.cwiseInverse();
    for (int k = 0; nu > 0 && nx + k * nu < count; ++k) {
      scale.segment(nx + k * nu, nu) = units.control.cwiseInverse();
    }
    return scale;
  };
  for (Eigen::MatrixXd& step : sensitivities.states) {
    if (step.rows() != units.state.size()) continue;
    step = units.state.asDiagonal() * step * columns(step.cols()).asDiagonal();
  }
  for (Eigen::RowVectorXd& row : sensitivities.switch_times) {
    row = row * columns(row.size()).asDiagonal();
  }
}

void scaleOutcome(SceneOutcome& outcome, const SolveUnits& units) {
  const double length = units.length;
  for (PairDecision& decision : outcome.decisions) decision.min_distance *= length;
  scalePlannedPushes(outcome, length);
  scaleTrajectory(outcome.trajectory, outcome.modelled, units);
  outcome.report.objective *= length * length;
  for (HomotopyStep& step : outcome.report.history) step.objective *= length * length;
  outcome.boundary_gap *= length;
  scaleVerification(outcome.verification, units);
  scaleGrazes(outcome.guard_points, length);
  scaleGrazes(outcome.grazes, length);
  for (AccuracyRung& rung : outcome.refinements) {
    rung.verification_error *= length;
    rung.error_before *= length;
  }
  scaleSensitivities(outcome.sensitivities, units);
  for (double& distance : outcome.target_distances) distance *= length;
  for (size_t j = 0; j < outcome.joint_target_distances.size(); ++j) {
    outcome.joint_target_distances[j] *= units.state(j);
  }
}

}  // namespace

void scaleTrajectory(Trajectory& trajectory, const std::vector<ContactPair>& pairs,
                     const SolveUnits& units) {
  Eigen::VectorXd constraint_factors(pairs.size()), multiplier_factors(pairs.size());
  for (size_t k = 0; k < pairs.size(); ++k) {
    const double power = constraintPower(pairs[k]);
    constraint_factors(k) = std::pow(units.length, power);
    multiplier_factors(k) = std::pow(units.length, 2.0 - power);
  }
  for (Eigen::VectorXd& x : trajectory.states) x = x.cwiseProduct(units.state);
  for (Eigen::VectorXd& u : trajectory.controls) u = u.cwiseProduct(units.control);
  for (ElementValues& element : trajectory.elements) {
    element.stage_states = units.state.asDiagonal() * element.stage_states;
    scaleRows(element.stage_multipliers, multiplier_factors);
    scaleRows(element.stage_constraints, constraint_factors);
    element.lowest_constraints *= units.length;
  }
}

void outcomeToUserUnits(SceneOutcome& outcome, const SolveUnits& units) {
  scaleOutcome(outcome, units);
}

void outcomeToSolveUnits(SceneOutcome& outcome, const SolveUnits& units) {
  scaleOutcome(outcome, raised(units, -1.0));
}

SceneOutcome solveInLengthUnits(
    const SceneTask& task, const SceneSolveOptions& given,
    const std::function<SceneOutcome(const SceneTask&, const SceneSolveOptions&)>& solve) {
  const SceneTask scaled = taskInLengthUnits(task, lengthScale(task));
  const SolveUnits units = solveUnits(scaled.scene);
  SceneSolveOptions options = given;
  options.length_scaling = false;
  // The earlier outcomes the solve starts from, in its units (owned here).
  std::unique_ptr<SceneOutcome> previous, refine;
  if (options.previous) {
    previous = std::make_unique<SceneOutcome>(*options.previous);
    outcomeToSolveUnits(*previous, units);
    options.previous = previous.get();
  }
  if (options.refine) {
    refine = std::make_unique<SceneOutcome>(*options.refine);
    outcomeToSolveUnits(*refine, units);
    options.refine = refine.get();
  }
  // The monitor is told each step's objective in the task's units, as the outcome.
  SolveMonitor monitor;
  if (options.monitor) {
    monitor.cancel = options.monitor->cancel;
    monitor.on_step = [&, told = options.monitor](const HomotopyStep& step) {
      HomotopyStep scaled_step = step;
      scaled_step.objective *= units.length * units.length;
      if (told->on_step) told->on_step(scaled_step);
    };
    options.monitor = &monitor;
  }
  SceneOutcome outcome = solve(scaled, options);
  outcomeToUserUnits(outcome, units);
  outcome.length_scale = units.length;
  return outcome;
}

}  // namespace fesd
