#include "fesd_trajopt/planning/scene_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "fesd_trajopt/planning/push_plan.h"
#include "fesd_trajopt/planning/robot_guess.h"
#include "fesd_trajopt/scene/lazy_pairs.h"
#include "fesd_trajopt/scene/moving_part.h"
#include "fesd_trajopt/scene/pair_check.h"
#include "fesd_trajopt/solver/memory_estimate.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {
namespace {

/// Validation, infeasibility and the pair decisions: what both entry points do before solving.
/// False when the task is not to be solved.
bool prepare(const SceneTask& task, const TaskLimits& limits, bool check_goals,
             SceneOutcome& outcome) {
  outcome.invalid = validateTask(task, limits);
  if (!outcome.invalid.empty()) return false;
  if (check_goals) outcome.infeasible = infeasibility(task);
  if (!outcome.infeasible.empty()) return false;
  outcome.decisions = decidePairs(task);
  return true;
}

MovingPart movingPartOf(const SceneTask& task, SceneOutcome& outcome) {
  MovingPart part = movingPart(task, outcome.decisions);
  outcome.moving_bodies = part.bodies;
  return part;
}

PlanStructure planStructure(const SceneTask& task, const SceneOutcome& outcome,
                            const DiscretizationOptions& discretization) {
  std::vector<std::string> moving, pairs;
  for (int j = 0; j < task.scene.numJoints(); ++j) {
    moving.push_back("joint " + task.scene.robot().joints[j].name);
  }
  for (int b : outcome.moving_bodies) moving.push_back(movingBodyName(task.scene.bodies()[b]));
  for (const PairDecision& decision : outcome.decisions) {
    if (decision.modelled) pairs.push_back(task.scene.pairName(decision.pair));
  }
  return planStructure(std::move(moving), std::move(pairs), task.horizon, task.num_intervals,
                       discretization);
}

/// The pairs of the decisions that are modelled, in their order.
std::vector<ContactPair> modelledPairs(const std::vector<PairDecision>& decisions) {
  std::vector<ContactPair> pairs;
  for (const PairDecision& decision : decisions) {
    if (decision.modelled) pairs.push_back(decision.pair);
  }
  return pairs;
}

/// A deterministic first guess of the pairs in reach: the push plan, or for a robot the inverse
/// kinematics of its pushing sphere's push plan.
struct FirstGuess {
  TrajectoryGuess guess;  ///< multipliers per pair in reach
  std::vector<PushPlan::ShortPush> short_pushes;
  int pusher_sphere = -1;
  std::vector<PushLeg> legs;  ///< of a push plan of free bodies
  std::vector<Transit> transits;
};

FirstGuess firstGuess(const SceneTask& task, const std::vector<ContactPair>& candidates,
                      const SceneSolveOptions& options) {
  if (task.scene.hasRobot()) {
    RobotGuess robot = planRobotGuess(task, candidates, options.ocp.discretization.num_elements);
    return {std::move(robot.guess), {}, robot.pusher_sphere, {}, {}};
  }
  PushPlan plan = planPushes(task, candidates);
  return {std::move(plan.guess), std::move(plan.short_pushes), -1, std::move(plan.legs),
          std::move(plan.transits)};
}

/// The first round's pairs, among the pairs in reach (the decisions' modelled ones): all of them
/// without lazy pairs or with few in reach; for a warm start the previous solution's pairs when
/// all of them are in reach (so that its NLP can be the same); else those the first guess calls
/// for. The others in reach are to be checked.
void chooseFirstPairs(const SceneTask& task, const std::vector<ContactPair>& candidates,
                      const TrajectoryGuess& guess, const SceneSolveOptions& options,
                      SceneOutcome& outcome) {
  if (!options.lazy_pairs || static_cast<int>(candidates.size()) <= options.all_pairs_up_to) {
    return;
  }
  std::vector<bool> chosen;
  std::vector<std::string> reasons(candidates.size(),
                                   "modelled in the previous solution (warm start)");
  if (options.previous) {
    std::vector<std::string> names;
    for (const ContactPair& pair : candidates) names.push_back(task.scene.pairName(pair));
    chosen = previousPairsAmong(names, options.previous->structure.modelled_pairs);
  }
  if (chosen.size() != candidates.size()) {
    const int samples = 16 * task.num_intervals;
    const PairSelection selection = pairsTheGuessNeeds(task.scene, task.horizon, candidates, guess,
                                                       options.pair_margin, samples);
    chosen = selection.modelled;
    reasons = selection.reasons;
  }
  size_t k = 0;
  for (PairDecision& decision : outcome.decisions) {
    if (!decision.modelled) continue;
    decision.modelled = chosen[k];
    decision.checked = !chosen[k];
    if (chosen[k]) decision.reason = reasons[k];
    ++k;
  }
}

/// Each body's distance from its target at the end; a successful outcome that misses one by more
/// than targetTolerance is kTargetNotReached, its message naming every target missed.
/// Why an NLP is refused before Ipopt starts (its estimated memory beyond the limit), or "".
std::string nlpTooLarge(const NlpAssembly& nlp, size_t modelled_pairs, const SceneTask& task,
                        const SceneSolveOptions& options, const TaskLimits& limits) {
  const double mib =
      estimatedSolverMib(nlp, task.num_intervals * options.ocp.discretization.num_elements);
  if (mib <= limits.max_solver_mib) return "";
  std::ostringstream message;
  message << "the NLP is too large to solve here: about " << static_cast<long>(mib)
          << " MiB estimated for its solve (" << nlp.numVariables() << " variables, "
          << nlp.numConstraints() << " constraints, " << modelled_pairs
          << " modelled contact pairs) > limits/max_solver_mib " << limits.max_solver_mib;
  return message.str();
}

/// The task with each target the push plan found out of the pushers' reach replaced by the
/// nearest end it pushes to.
SceneTask reachableTask(const SceneTask& task, const FirstGuess& guess) {
  SceneTask reachable = task;
  for (const PushPlan::ShortPush& push : guess.short_pushes) {
    // Out of time only: the real target's optimum pushes as far as time allows, as planned.
    if (!push.time_limited) reachable.bodies[push.body].target = push.end;
  }
  return reachable;
}

/// Each body's and joint's distance from its target at the end; a successful outcome that misses
/// one by more than targetTolerance is kTargetNotReached, its message naming every target missed
/// (and why, for the pushes the first guess found short).
void judgeTargets(const SceneTask& task, SceneOutcome& outcome, const FirstGuess& guess) {
  const Scene& scene = task.scene;
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
  outcome.target_distances.assign(scene.bodies().size(), nan);
  for (size_t b = 0; b < scene.bodies().size(); ++b) {
    const BodyTask& t = task.bodies[b];
    if (!t.hasTarget()) continue;
    const double distance = (scene.position(static_cast<int>(b), end) - t.target).norm();
    outcome.target_distances[b] = distance;
    if (distance <= targetTolerance(t.target_weight)) continue;
    missed << (missed.tellp() > 0 ? "; " : "") << "body '" << scene.bodies()[b].name << "' ends "
           << distance << " from its target (" << t.target.transpose() << "), tolerance "
           << targetTolerance(t.target_weight);
    for (const PushPlan::ShortPush& push : guess.short_pushes) {
      if (push.body != static_cast<int>(b)) continue;
      missed << (push.time_limited
                     ? " (out of the pushers' reach within the horizon at their speed bounds; "
                       "planned as far towards it as time allows, ("
                     : " (out of the pushers' reach: workspace bounds, obstacles or walls; planned "
                       "to the nearest end they can push it to, (")
             << push.end.transpose() << "))";
    }
  }
  if (outcome.status == SolveStatus::kSuccess && missed.tellp() > 0) {
    outcome.status = SolveStatus::kTargetNotReached;
    outcome.message = "target not reached: " + missed.str() + "; " + outcome.message;
  }
}

/// Every pair in reach (modelled or checked) measured along the outcome's trajectory, between
/// element boundaries too. After a successful round, the checked pairs that came within the
/// margin become modelled for the next round (named in `rounds_note`): true when there is one.
bool measureGaps(const SceneTask& task, const SceneSolveOptions& options, int round,
                 SceneOutcome& outcome, std::string& rounds_note) {
  std::vector<ContactPair> modelled, checked;
  for (const PairDecision& decision : outcome.decisions) {
    if (decision.modelled) modelled.push_back(decision.pair);
    if (decision.checked) checked.push_back(decision.pair);
  }
  const std::vector<double> modelled_gaps =
      smallestGapsAt(task.scene, modelled, densePath(outcome.trajectory, 0));
  const std::vector<double> checked_gaps =
      smallestGaps(task.scene, checked, densePath(outcome.trajectory));
  std::vector<std::string> added;
  size_t m = 0, c = 0;
  for (PairDecision& decision : outcome.decisions) {
    if (decision.modelled) {
      decision.min_distance = modelled_gaps[m++];
      continue;
    }
    if (!decision.checked) continue;
    decision.min_distance = checked_gaps[c++];
    std::ostringstream reason;
    reason.precision(3);
    if (outcome.status == SolveStatus::kSuccess &&
        withinMargin(task.scene, decision.pair, decision.min_distance, options.pair_margin)) {
      reason << "modelled from round " << round + 1 << ": came within " << decision.min_distance
             << " in round " << round;
      decision.modelled = true;
      decision.checked = false;
      added.push_back(task.scene.pairName(decision.pair));
    } else {
      reason << "checked on the solution: never closer than " << decision.min_distance
             << " (margin " << options.pair_margin * task.scene.pairSize(decision.pair) << ")";
    }
    decision.reason = reason.str();
  }
  if (!added.empty()) {
    std::string names;
    for (const std::string& name : added) names += (names.empty() ? "" : ", ") + name;
    rounds_note += "; round " + std::to_string(round + 1) + " added " + names;
  }
  return !added.empty();
}

/// The smallest sigma of the report's relaxed NLPs that converged, or `fallback` when none did.
double tightestRelaxation(const MpccReport& report, double fallback) {
  double sigma = fallback;
  for (const HomotopyStep& step : report.history) {
    if (step.converged && step.sigma > 0.0) sigma = std::min(sigma, step.sigma);
  }
  return sigma;
}

}  // namespace

std::string warmStartRefusal(const SceneOutcome& previous, const SceneOutcome& now) {
  return warmStartRefusal(previous.solved() && solvedItsNlp(previous.status),
                          static_cast<int>(previous.report.solution.size()), previous.sizes,
                          previous.structure, now.sizes, now.structure);
}

SceneOutcome solveSceneTask(const SceneTask& task, const TaskLimits& limits,
                            const SceneSolveOptions& options) {
  Stopwatch stopwatch;
  SceneOutcome outcome;
  if (!prepare(task, limits, true, outcome)) return outcome;
  if (!options.prune_pairs) {
    for (PairDecision& decision : outcome.decisions) decision.modelled = true;
  }
  const std::vector<ContactPair> candidates = modelledPairs(outcome.decisions);
  const FirstGuess first_guess = firstGuess(task, candidates, options);
  outcome.pusher_sphere = first_guess.pusher_sphere;
  outcome.planned_legs = first_guess.legs;
  outcome.planned_transits = first_guess.transits;
  // A soft target out of the pushers' reach: the OCP aims at the nearest end the plan can push
  // to (a reachable task, solved as fast as one), and the answer is judged by the real target.
  const SceneTask aimed = reachableTask(task, first_guess);
  chooseFirstPairs(aimed, candidates, first_guess.guess, options, outcome);
  Trajectory previous_round;
  std::vector<ContactPair> previous_pairs;
  std::string rounds_note;
  for (int round = 1;; ++round) {
    const MovingPart part = movingPartOf(aimed, outcome);
    const OcpDefinition ocp = buildOcp(part.task, part.modelled);
    OcpOptions ocp_options = options.ocp;
    ocp_options.homotopy.wall_time_budget =
        std::max(0.0, options.ocp.homotopy.wall_time_budget - stopwatch.wallSeconds());
    if (round > 1 && !task.scene.hasRobot()) {
      // The previous round's solution is nearly this round's (the new pairs start separated):
      // its homotopy resumes at the tightest relaxation that round reached, not from guess_sigma.
      // Same optima on the planning sweep, in less time; a robot's lazy round starts over: on
      // the arm push resuming ended in another local optimum (objective 2.0e-4 against 1.4e-4).
      ocp_options.guess_sigma = tightestRelaxation(outcome.report, ocp_options.guess_sigma);
    }
    OcpSolver solver(ocp, ocp_options);
    solver.setMonitor(options.monitor);
    const NlpAssembly& nlp = solver.discretization().nlp();
    outcome.sizes = {nlp.numVariables(), nlp.numConstraints(), nlp.numComplementarities()};
    const std::string too_large = nlpTooLarge(nlp, part.modelled.size(), task, options, limits);
    if (!too_large.empty() && round == 1) {
      outcome.invalid = too_large + "; ask for fewer intervals, elements or stages";
      return outcome;
    }
    if (!too_large.empty()) {
      outcome.status = SolveStatus::kSolverError;
      outcome.message = "pair round " + std::to_string(round) + ": " + too_large +
                        "; the plan of the round before comes within the margin of pairs it does "
                        "not model";
      break;
    }
    outcome.structure = planStructure(aimed, outcome, options.ocp.discretization);
    const TrajectoryGuess guess = partGuess(aimed, part, first_guess.guess, candidates);
    OcpSolution solution;
    if (round == 1) {
      if (options.previous != nullptr) {
        outcome.cold_start_reason = warmStartRefusal(*options.previous, outcome);
      }
      const bool warm = options.previous != nullptr && outcome.cold_start_reason.empty();
      OcpSolution previous;
      if (warm) previous.report = options.previous->report;
      solution = warm ? solver.solve(previous, guess) : solver.solve(guess);
      if (warm && solution.start != OcpStart::kPrevious) {
        outcome.cold_start_reason = "the warm solve failed";
      }
      outcome.warm_started = solution.start == OcpStart::kPrevious;
      outcome.guess_residual = solution.guess_residual;
    } else {
      solution = solver.solve(partTrajectory(aimed, part, previous_round, previous_pairs), guess);
      solution.report.history.insert(solution.report.history.begin(),
                                     outcome.report.history.begin(), outcome.report.history.end());
      solution.report.addEffort(outcome.report);
    }
    outcome.status = solution.status;
    outcome.message = solution.message;
    outcome.start = solution.start;
    outcome.trajectory = fullSceneTrajectory(aimed, part, solution.trajectory);
    outcome.report = solution.report;
    outcome.pair_rounds = round;
    outcome.modelled = part.modelled_in_task;
    previous_round = outcome.trajectory;
    previous_pairs = part.modelled_in_task;
    if (!measureGaps(aimed, options, round, outcome, rounds_note)) break;
  }
  outcome.message += rounds_note;
  if (!outcome.trajectory.states.empty()) {
    outcome.boundary_gap = smallestBoundaryGap(task.scene, outcome.modelled, outcome.trajectory);
  }
  judgeTargets(task, outcome, first_guess);
  if (options.verify && outcome.status != SolveStatus::kCancelled) {
    const SimulationOptions fine =
        verificationOptions(options.verification, options.ocp,
                            options.ocp.homotopy.wall_time_budget - stopwatch.wallSeconds());
    const Verification verification = verifyOutcome(task, outcome, fine, options.pair_margin);
    outcome.verified = true;
    outcome.verification_error = verification.error;
    outcome.verification_gap = verification.gap;
  }
  return outcome;
}

double smallestBoundaryGap(const Scene& scene, const std::vector<ContactPair>& pairs,
                           const Trajectory& trajectory) {
  double gap = std::numeric_limits<double>::infinity();
  for (double at : smallestGapsAt(scene, pairs, trajectory.states)) gap = std::min(gap, at);
  return gap;
}

SimulationOptions verificationOptions(const DiscretizationOptions& configured,
                                      const OcpOptions& solve, double remaining_budget) {
  const DiscretizationOptions& solved = solve.discretization;
  SimulationOptions fine;
  fine.discretization = configured;
  fine.homotopy.ipopt.linear_solver = solve.homotopy.ipopt.linear_solver;
  fine.retry_homotopy.ipopt.linear_solver = solve.homotopy.ipopt.linear_solver;
  // The reference must be finer than the solve, or its own error is what gets measured (the
  // configured n_s = 3, N_FE = 6 showed 1.4e-6 against n_s = 4 solves of any N_FE).
  fine.discretization.num_stages = std::max(fine.discretization.num_stages, solved.num_stages);
  fine.discretization.num_elements =
      std::max(fine.discretization.num_elements, 2 * solved.num_elements);
  // 0 when the solve used it all: the re-simulation times out and its error is infinite.
  fine.wall_time_budget = std::max(0.0, remaining_budget);
  return fine;
}

Verification verifyOutcome(const SceneTask& task, const SceneOutcome& outcome,
                           const SimulationOptions& fine, double margin) {
  Stopwatch stopwatch;
  std::vector<PairDecision> decisions = outcome.decisions;
  Verification verification;
  for (bool grew = true; grew;) {
    const MovingPart part = movingPart(task, decisions);
    SimulationOptions remaining = fine;
    remaining.wall_time_budget = std::max(0.0, fine.wall_time_budget - stopwatch.wallSeconds());
    const SimulationResult result =
        resimulate(buildOcp(part.task, part.modelled), outcome.trajectory.controls, remaining);
    verification.status = result.status;
    verification.trajectory = fullSceneTrajectory(task, part, result.trajectory);
    verification.modelled_pairs = static_cast<int>(part.modelled.size());
    if (result.status != SolveStatus::kSuccess) return verification;
    // No pair left to check: the dense path (~10 % of the rest) is not needed.
    if (std::none_of(decisions.begin(), decisions.end(),
                     [](const PairDecision& d) { return d.checked; })) {
      break;
    }
    grew = false;
    std::vector<ContactPair> checked;
    for (const PairDecision& decision : decisions) {
      if (decision.checked) checked.push_back(decision.pair);
    }
    const std::vector<double> gaps =
        smallestGaps(task.scene, checked, densePath(verification.trajectory));
    size_t k = 0;
    for (PairDecision& decision : decisions) {
      if (!decision.checked) continue;
      if (withinMargin(task.scene, decision.pair, gaps[k++], margin)) {
        decision.modelled = true;
        decision.checked = false;
        grew = true;
      }
    }
  }
  verification.error =
      (verification.trajectory.finalState() - outcome.trajectory.finalState()).norm();
  std::vector<ContactPair> in_reach;
  for (const PairDecision& decision : outcome.decisions) {
    if (decision.modelled || decision.checked) in_reach.push_back(decision.pair);
  }
  verification.gap = smallestBoundaryGap(task.scene, in_reach, verification.trajectory);
  return verification;
}

SceneOutcome simulateSceneTask(SceneTask task, const std::vector<Eigen::VectorXd>& controls,
                               const TaskLimits& limits, const SimulationOptions& options) {
  const int steps = task.num_intervals;
  SceneOutcome outcome;
  if (controls.size() != 1 && static_cast<int>(controls.size()) != steps) {
    outcome.invalid = "the controls must be one for all steps or one per step";
    return outcome;
  }
  for (const Eigen::VectorXd& u : controls) {
    if (u.size() != task.scene.controlSize() || !u.allFinite()) {
      outcome.invalid = "every control must be finite and of the scene's control size";
      return outcome;
    }
  }
  const int dim = task.scene.dimension();
  for (size_t b = 0; b < task.bodies.size(); ++b) {
    BodyTask& body = task.bodies[b];
    body.workspace_lower.resize(0);
    body.workspace_upper.resize(0);
    body.max_speed = 0.0;
    if (b >= task.scene.bodies().size() || !task.scene.bodies()[b].actuated) continue;
    for (const Eigen::VectorXd& u : controls) {
      const int first = task.scene.controlIndex(static_cast<int>(b));
      body.max_speed = std::max(body.max_speed, u.segment(first, dim).cwiseAbs().maxCoeff());
    }
  }
  for (int j = 0; j < task.scene.numJoints() && j < static_cast<int>(task.joints.size()); ++j) {
    double speed = 0.0;
    for (const Eigen::VectorXd& u : controls) speed = std::max(speed, std::fabs(u(j)));
    task.joints[j].passive = speed == 0.0;
    task.joints[j].max_velocity = speed;
  }
  if (!prepare(task, limits, false, outcome)) return outcome;
  const MovingPart part = movingPartOf(task, outcome);
  const Scene& moving = part.task.scene;
  FesdIntegrator integrator(moving.model(part.modelled), options);
  const SimulationResult result =
      integrator.simulate(moving.initialState(), task.horizon, steps, controls);
  outcome.modelled = part.modelled_in_task;
  outcome.status = result.status;
  outcome.message = result.message;
  outcome.trajectory = fullSceneTrajectory(task, part, result.trajectory);
  outcome.report = result.totals;
  if (options.sensitivities) {
    outcome.sensitivities = fullSceneSensitivities(task, part, result.sensitivities);
  }
  return outcome;
}

}  // namespace fesd
