#include "fesd_trajopt/scene/robot_solver.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fesd_trajopt/scene/robot_guess.h"
#include "fesd_trajopt/scene/robot_lazy_pairs.h"
#include "fesd_trajopt/scene/scene_solver.h"
#include "fesd_trajopt/solver/stopwatch.h"

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

/// What a warm start needs unchanged: the joints, the free bodies, the modelled pairs and the
/// discretisation.
PlanStructure robotPlanStructure(const RobotTask& task, const std::vector<RobotPair>& modelled,
                                 const DiscretizationOptions& discretization) {
  const RobotScene& scene = task.scene;
  std::vector<std::string> moving, pairs;
  for (const KinematicJoint& joint : scene.robot().joints) moving.push_back("joint " + joint.name);
  for (const SceneBody& body : scene.discs().bodies()) moving.push_back(movingBodyName(body));
  for (const RobotPair& pair : modelled) pairs.push_back(scene.pairName(pair));
  return planStructure(std::move(moving), std::move(pairs), task.horizon, task.num_intervals,
                       discretization);
}

/// Lazy pairs' first round, of the candidates: the pairs the previous plan ended with when there
/// is one to warm-start from and all of them are still candidates (so that its NLP can match),
/// else those the first guess calls for; `why` says which.
std::vector<bool> firstLazyPairs(const RobotTask& task, const std::vector<RobotPair>& candidates,
                                 const TrajectoryGuess& guess, const RobotSolveOptions& options,
                                 std::string& why) {
  if (options.previous != nullptr) {
    std::vector<std::string> names;
    for (const RobotPair& pair : candidates) names.push_back(task.scene.pairName(pair));
    std::vector<bool> chosen =
        previousPairsAmong(names, options.previous->structure.modelled_pairs);
    if (chosen.size() == candidates.size()) {
      why = "modelled in the previous solution (warm start)";
      return chosen;
    }
  }
  why = "called for by the first guess";
  return robotPairsTheGuessNeeds(task, candidates, guess, options.pair_margin,
                                 16 * task.num_intervals);
}

/// The first round's solve: warm from options.previous when it fits, else from the guess.
OcpSolution firstRound(OcpSolver& solver, const TrajectoryGuess& guess,
                       const RobotSolveOptions& options, RobotOutcome& outcome) {
  const RobotOutcome* previous = options.previous;
  if (previous == nullptr) return solver.solve(guess);
  outcome.cold_start_reason =
      warmStartRefusal(previous->invalid.empty() && solvedItsNlp(previous->status),
                       static_cast<int>(previous->report.solution.size()), previous->sizes,
                       previous->structure, outcome.sizes, outcome.structure);
  if (!outcome.cold_start_reason.empty()) return solver.solve(guess);
  OcpSolution warm;
  warm.report = previous->report;
  OcpSolution solution = solver.solve(warm, guess);
  outcome.warm_started = solution.start == OcpStart::kPrevious;
  if (!outcome.warm_started) outcome.cold_start_reason = "the warm solve failed";
  return solution;
}

/// Sets min_distance of the modelled (or the checked) decisions to their smallest gap along
/// the path, with one forward kinematics per state for all of them.
void measureGaps(const RobotScene& scene, const std::vector<Eigen::VectorXd>& path, bool modelled,
                 std::vector<RobotPairDecision>& decisions) {
  std::vector<RobotPair> pairs;
  std::vector<RobotPairDecision*> measured;
  for (RobotPairDecision& decision : decisions) {
    if (modelled ? decision.modelled : decision.checked) {
      pairs.push_back(decision.pair);
      measured.push_back(&decision);
    }
  }
  const std::vector<double> gaps = smallestPathGaps(scene, pairs, path);
  for (size_t k = 0; k < measured.size(); ++k) measured[k]->min_distance = gaps[k];
}

/// Adds to `simulated` the pairs of `candidates` that come within the margin along the path;
/// whether it added any.
bool addPairsWithinMargin(const RobotScene& scene, const std::vector<RobotPair>& candidates,
                          const std::vector<Eigen::VectorXd>& path, double margin,
                          std::vector<RobotPair>& simulated) {
  const std::vector<double> gaps = smallestPathGaps(scene, candidates, path);
  bool added = false;
  for (size_t k = 0; k < candidates.size(); ++k) {
    if (!robotWithinMargin(scene, candidates[k], gaps[k], margin) ||
        std::find(simulated.begin(), simulated.end(), candidates[k]) != simulated.end()) {
      continue;
    }
    simulated.push_back(candidates[k]);
    added = true;
  }
  return added;
}

/// The plan's controls re-simulated on the fine grid with the pairs in reach that come within
/// the margin along the plan, again with those that come within it along the re-simulation,
/// until none more does: the motion of the model with every pair in reach, at the cost of the
/// few that matter (a Panda push: 7 pairs of 118).
void verifyRobotPlan(const RobotTask& task, const std::vector<RobotPair>& candidates,
                     const SimulationOptions& fine, double margin, RobotOutcome& outcome) {
  Stopwatch stopwatch;
  std::vector<RobotPair> simulated;
  addPairsWithinMargin(task.scene, candidates, densePath(outcome.trajectory), margin, simulated);
  for (;;) {
    SimulationOptions remaining = fine;
    remaining.wall_time_budget = std::max(0.0, fine.wall_time_budget - stopwatch.wallSeconds());
    const SimulationResult result =
        resimulate(buildRobotOcp(task, simulated), outcome.trajectory.controls, remaining);
    if (result.status != SolveStatus::kSuccess) {
      outcome.verification_error = std::numeric_limits<double>::infinity();
      return;
    }
    if (addPairsWithinMargin(task.scene, candidates, densePath(result.trajectory), margin,
                             simulated)) {
      continue;
    }
    outcome.verification_error =
        (result.trajectory.finalState() - outcome.trajectory.finalState()).norm();
    outcome.verification_gap = smallestBoundaryGap(task.scene, candidates, result.trajectory);
    return;
  }
}

}  // namespace

double smallestBoundaryGap(const RobotScene& scene, const std::vector<RobotPair>& pairs,
                           const Trajectory& trajectory) {
  double gap = std::numeric_limits<double>::infinity();
  for (const Eigen::VectorXd& x : trajectory.states) {
    for (double at : scene.pairGaps(pairs, x)) gap = std::min(gap, at);
  }
  return gap;
}

RobotOutcome solveRobotTask(const RobotTask& task, const TaskLimits& limits,
                            const RobotSolveOptions& options) {
  RobotOutcome outcome;
  outcome.invalid = validateRobotTask(task, limits);
  if (!outcome.invalid.empty()) return outcome;
  outcome.decisions = decideRobotPairs(task);
  std::vector<RobotPair> candidates;
  for (const RobotPairDecision& decision : outcome.decisions) {
    if (decision.modelled) candidates.push_back(decision.pair);
  }
  const int elements = options.ocp.discretization.num_elements;
  const RobotGuess guess = planRobotGuess(task, candidates, elements);
  outcome.pusher_sphere = guess.pusher_sphere;
  if (options.lazy_pairs && static_cast<int>(candidates.size()) > options.all_pairs_up_to) {
    std::string why;
    const std::vector<bool> needed = firstLazyPairs(task, candidates, guess.guess, options, why);
    size_t k = 0;
    for (RobotPairDecision& decision : outcome.decisions) {
      if (!decision.modelled) continue;
      decision.modelled = needed[k];
      decision.checked = !needed[k];
      decision.reason = needed[k] ? why : "checked on the solution";
      ++k;
    }
  }
  Stopwatch stopwatch;
  Trajectory previous_round;
  std::vector<RobotPair> previous_pairs;
  for (int round = 1;; ++round) {
    outcome.modelled.clear();
    for (const RobotPairDecision& decision : outcome.decisions) {
      if (decision.modelled) outcome.modelled.push_back(decision.pair);
    }
    const OcpDefinition ocp = buildRobotOcp(task, outcome.modelled);
    OcpOptions ocp_options = options.ocp;
    ocp_options.homotopy.wall_time_budget =
        std::max(0.0, options.ocp.homotopy.wall_time_budget - stopwatch.wallSeconds());
    OcpSolver solver(ocp, ocp_options);
    solver.setMonitor(options.monitor);
    const NlpAssembly& nlp = solver.discretization().nlp();
    outcome.sizes = {nlp.numVariables(), nlp.numConstraints(), nlp.numComplementarities()};
    outcome.structure = robotPlanStructure(task, outcome.modelled, options.ocp.discretization);
    // The guess's multipliers belong to the candidates; the NLP's to the modelled pairs.
    TrajectoryGuess round_guess = planRobotGuess(task, outcome.modelled, elements).guess;
    OcpSolution solution =
        round == 1
            ? firstRound(solver, round_guess, options, outcome)
            : solver.solve(trajectoryForPairs(previous_round, previous_pairs, outcome.modelled),
                           round_guess);
    if (round > 1) solution.report.addEffort(outcome.report);
    outcome.status = solution.status;
    outcome.message = solution.message;
    outcome.start = solution.start;
    outcome.trajectory = solution.trajectory;
    outcome.report = solution.report;
    outcome.pair_rounds = round;
    if (outcome.trajectory.states.empty() || outcome.status != SolveStatus::kSuccess) break;
    previous_round = outcome.trajectory;
    previous_pairs = outcome.modelled;
    // Checked pairs that came within the margin along the solution are modelled next round.
    measureGaps(task.scene, densePath(outcome.trajectory), false, outcome.decisions);
    bool added = false;
    for (RobotPairDecision& decision : outcome.decisions) {
      if (!decision.checked || !robotWithinMargin(task.scene, decision.pair, decision.min_distance,
                                                  options.pair_margin)) {
        continue;
      }
      decision.modelled = true;
      decision.checked = false;
      decision.reason = "modelled from round " + std::to_string(round + 1);
      added = true;
    }
    if (!added) break;
  }
  if (outcome.trajectory.states.empty()) return outcome;
  outcome.boundary_gap = smallestBoundaryGap(task.scene, outcome.modelled, outcome.trajectory);
  // A modelled pair's gap at the stage points (where the plan holds it), a checked one's
  // measured by the last round's check, unless that round failed before its check.
  measureGaps(task.scene, densePath(outcome.trajectory, 0), true, outcome.decisions);
  if (outcome.status != SolveStatus::kSuccess) {
    for (RobotPairDecision& decision : outcome.decisions) {
      if (decision.checked) decision.min_distance = std::numeric_limits<double>::quiet_NaN();
    }
  }
  judgeTargets(task, outcome);
  if (options.verify && outcome.status != SolveStatus::kCancelled) {
    const SimulationOptions fine =
        verificationOptions(options.verification, options.ocp,
                            options.ocp.homotopy.wall_time_budget - stopwatch.wallSeconds());
    verifyRobotPlan(task, candidates, fine, options.pair_margin, outcome);
  }
  return outcome;
}

RobotOutcome solveRobotToAccuracy(const RobotTask& task, const TaskLimits& limits,
                                  RobotSolveOptions options, double target_accuracy) {
  options.verify = true;
  const RobotOutcome* previous = options.previous;
  if (previous && solvedItsNlp(previous->status) && !std::isnan(previous->verification_error)) {
    startOnPreviousRung(previous->structure, options.ocp.discretization);
  }
  return climbAccuracyLadder<RobotOutcome>(
      options, limits, target_accuracy,
      [&](const RobotSolveOptions& rung) { return solveRobotTask(task, limits, rung); },
      [](const RobotOutcome& outcome) { return !outcome.invalid.empty(); });
}

}  // namespace fesd
