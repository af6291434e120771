#include "fesd_trajopt/scene/robot_solver.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fesd_trajopt/scene/robot_guess.h"

namespace fesd {
namespace {

/// Distances from the targets; a success that misses one becomes kTargetNotReached.
void judgeTargets(const RobotTask& task, RobotOutcome& outcome) {
  const RobotScene& scene = task.scene;
  const Eigen::VectorXd end = outcome.trajectory.finalState();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  std::ostringstream missed;
  missed.precision(3);
  outcome.joint_target_distances.assign(scene.numJoints(), nan);
  for (int j = 0; j < scene.numJoints(); ++j) {
    const JointTask& t = task.joints[j];
    if (!(t.target_weight > 0.0)) continue;
    outcome.joint_target_distances[j] = std::fabs(end(j) - t.target);
    if (outcome.joint_target_distances[j] > targetTolerance(t.target_weight)) {
      missed << (missed.tellp() > 0 ? "; " : "") << "joint '" << scene.robot().joints[j].name
             << "' ends " << outcome.joint_target_distances[j] << " from its target";
    }
  }
  const DiscScene& discs = scene.discs();
  outcome.target_distances.assign(discs.bodies().size(), nan);
  for (size_t b = 0; b < discs.bodies().size(); ++b) {
    const BodyTask& t = task.bodies[b];
    if (t.target.size() == 0 || !(t.target_weight > 0.0)) continue;
    const int first = scene.bodyStateIndex(static_cast<int>(b));
    outcome.target_distances[b] = (end.segment(first, scene.dimension()) - t.target).norm();
    if (outcome.target_distances[b] > targetTolerance(t.target_weight)) {
      missed << (missed.tellp() > 0 ? "; " : "") << "body '" << discs.bodies()[b].name << "' ends "
             << outcome.target_distances[b] << " from its target";
    }
  }
  if (outcome.status == SolveStatus::kSuccess && missed.tellp() > 0) {
    outcome.status = SolveStatus::kTargetNotReached;
    outcome.message = "target not reached: " + missed.str() + "; " + outcome.message;
  }
}

}  // namespace

double smallestBoundaryGap(const RobotScene& scene, const std::vector<RobotPair>& pairs,
                           const Trajectory& trajectory) {
  double gap = std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& x : trajectory.states) {
    for (const RobotPair& pair : pairs) gap = std::min(gap, scene.pairGap(pair, x));
  }
  return gap;
}

RobotOutcome solveRobotTask(const RobotTask& task, const TaskLimits& limits,
                            const RobotSolveOptions& options) {
  RobotOutcome outcome;
  outcome.invalid = validateRobotTask(task, limits);
  if (!outcome.invalid.empty()) return outcome;
  outcome.decisions = decideRobotPairs(task);
  for (const RobotPairDecision& decision : outcome.decisions) {
    if (decision.modelled) outcome.modelled.push_back(decision.pair);
  }
  const RobotGuess guess =
      planRobotGuess(task, outcome.modelled, options.ocp.discretization.num_elements);
  outcome.pusher_sphere = guess.pusher_sphere;
  const OcpDefinition ocp = buildRobotOcp(task, outcome.modelled);
  OcpSolver solver(ocp, options.ocp);
  const OcpSolution solution = solver.solve(guess.guess);
  outcome.status = solution.status;
  outcome.message = solution.message;
  outcome.trajectory = solution.trajectory;
  outcome.report = solution.report;
  if (outcome.trajectory.states.empty()) return outcome;
  outcome.boundary_gap = smallestBoundaryGap(task.scene, outcome.modelled, outcome.trajectory);
  judgeTargets(task, outcome);
  if (options.verify && outcome.status != SolveStatus::kCancelled) {
    SimulationOptions fine;
    fine.discretization = options.verification;
    const DiscretizationOptions& solved = options.ocp.discretization;
    fine.discretization.num_stages = std::max(fine.discretization.num_stages, solved.num_stages);
    fine.discretization.num_elements =
        std::max(fine.discretization.num_elements, 2 * solved.num_elements);
    const SimulationResult result = resimulate(ocp, outcome.trajectory.controls, fine);
    if (result.status == SolveStatus::kSuccess) {
      outcome.verification_error =
          (result.trajectory.finalState() - outcome.trajectory.finalState()).norm();
      outcome.verification_gap =
          smallestBoundaryGap(task.scene, outcome.modelled, result.trajectory);
    } else {
      outcome.verification_error = std::numeric_limits<double>::infinity();
    }
  }
  return outcome;
}

}  // namespace fesd
