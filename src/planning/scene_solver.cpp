#include "fesd_trajopt/planning/scene_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>
#include <stdexcept>

#include "fesd_trajopt/discretization/butcher_tableau.h"
#include "fesd_trajopt/discretization/refined_trajectory.h"
#include "fesd_trajopt/planning/length_units.h"
#include "fesd_trajopt/planning/push_plan.h"
#include "fesd_trajopt/planning/robot_guess.h"
#include "fesd_trajopt/planning/support_check.h"
#include "fesd_trajopt/scene/lazy_pairs.h"
#include "fesd_trajopt/scene/moving_part.h"
#include "fesd_trajopt/scene/pair_check.h"
#include "fesd_trajopt/scene/scene_units.h"
#include "fesd_trajopt/solver/memory_estimate.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {
namespace {

/// A lazy-pair round resumes its homotopy no tighter than this: its new pairs may have been cut
/// into, which a nearly complementary start is slow to mend.
constexpr double kTightestResumedRelaxation = 1e-4;

/// A replan's polish of its previous plan's active set stops after this many Ipopt iterations:
/// from the plant's state, off the plan, cluttered seed 22's replans ran it to a cap of 50 or 100
/// and failed, the plan moved onto the plant's state after about 10, and the homotopy resumes
/// from there (docs/results.md: the closed loop's replans 3.06x -> 2.51x the first plan).
constexpr int kReplanPolishIterations = 20;

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
  for (int b : outcome.moving_bodies) {
    moving.push_back(movingBodyName(task.scene.bodies()[b], task.scene.length_unit));
  }
  for (const PairDecision& decision : outcome.decisions) {
    if (decision.modelled) pairs.push_back(task.scene.pairName(decision.pair));
  }
  return planStructure(std::move(moving), std::move(pairs), task.horizon, task.num_intervals,
                       discretization, task.scene.length_unit);
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
  bool turns_bodies = false;  ///< PushPlan::turns_bodies
};

FirstGuess firstGuess(const SceneTask& task, const std::vector<ContactPair>& candidates,
                      const SceneSolveOptions& options) {
  if (task.scene.hasRobot()) {
    RobotGuess robot = planRobotGuess(task, candidates, options.ocp.discretization.num_elements);
    return {std::move(robot.guess), {}, robot.pusher_sphere, {}, {}, robot.turns_bodies};
  }
  PushPlan plan = planPushes(task, candidates);
  return {std::move(plan.guess), std::move(plan.short_pushes), -1,
          std::move(plan.legs),  std::move(plan.transits),     plan.turns_bodies};
}

/// The first round's pairs, among the pairs in reach (the decisions' modelled ones): all of them
/// without lazy pairs or with few in reach; for a warm start the previous solution's pairs when
/// all of them are in reach (so that its NLP can be the same); else those the first guess calls
/// for, and every pair of a body with a target yaw unless the guess turns it. The others in
/// reach are to be checked.
void chooseFirstPairs(const SceneTask& task, const std::vector<ContactPair>& candidates,
                      const FirstGuess& first_guess, const SceneSolveOptions& options,
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
    const PairSelection selection =
        pairsTheGuessNeeds(task.scene, task.horizon, candidates, first_guess.guess,
                           options.first_round_margin, samples);
    chosen = selection.modelled;
    reasons = selection.reasons;
    // A push plan that does not turn bodies: a body with a yaw target gets its pairs in reach
    // modelled from the first round, so that the NLP can find the pushes that turn it.
    const std::vector<CollisionBody> bodies = task.scene.collisionBodies();
    const auto must_turn = [&](int collision_body) {
      const int body = bodies[collision_body].free_body;
      return body >= 0 && task.bodies[body].hasYawTarget() && !first_guess.turns_bodies;
    };
    for (size_t c = 0; c < candidates.size(); ++c) {
      const ContactPair& pair = candidates[c];
      if (chosen[c] || !(must_turn(pair.body) ||
                         (pair.kind == ContactPair::Kind::kBody && must_turn(pair.other)))) {
        continue;
      }
      chosen[c] = true;
      reasons[c] = "a pair of a body with a target yaw (the first guess does not turn it)";
    }
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

/// The elements of each control interval of the task on the options' grid.
std::vector<int> intervalElements(const SceneTask& task, const OcpOptions& options) {
  const DiscretizationOptions& grid = options.discretization;
  return grid.interval_elements.empty() ? std::vector<int>(task.num_intervals, grid.num_elements)
                                        : grid.interval_elements;
}

int totalElements(const SceneTask& task, const OcpOptions& options) {
  int total = 0;
  for (int count : intervalElements(task, options)) total += count;
  return total;
}

/// Why an NLP is refused before Ipopt starts (its estimated memory beyond the limit), or "".
std::string nlpTooLarge(const NlpAssembly& nlp, size_t modelled_pairs, const SceneTask& task,
                        const SceneSolveOptions& options, const TaskLimits& limits) {
  const double mib = estimatedSolverMib(nlp, totalElements(task, options.ocp));
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
/// (and why, for the pushes the first guess found short). Positions are judged in the scene's
/// units (relative to its length scale), angles in radians with the user's weights.
void judgeTargets(const SceneTask& task, SceneOutcome& outcome, const FirstGuess& guess) {
  const Scene& scene = task.scene;
  const Eigen::VectorXd end = outcome.trajectory.finalState();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double unit = scene.length_unit;
  std::ostringstream missed;
  missed.precision(3);
  outcome.joint_target_distances.assign(scene.numJoints(), nan);
  for (int j = 0; j < scene.numJoints(); ++j) {
    const JointTask& t = task.joints[j];
    if (!(t.target_weight > 0.0)) continue;
    outcome.joint_target_distances[j] = std::fabs(end(j) - t.target);
    // A revolute joint in radians with the user's weight (the solve's is that times
    // (its unit / length_unit)^2), a prismatic one as a length (relative to the length scale).
    const double joint_unit = scene.jointUnit(j);
    const double joint_distance = joint_unit * outcome.joint_target_distances[j];
    const double tolerance =
        scene.robot().joints[j].type == JointType::kPrismatic
            ? scene.userLength(targetTolerance(t.target_weight))
            : targetTolerance(t.target_weight * unit * unit / (joint_unit * joint_unit));
    if (joint_distance > tolerance) {
      missed << (missed.tellp() > 0 ? "; " : "") << "joint '" << scene.robot().joints[j].name
             << "' ends " << joint_distance << " from its target";
    }
  }
  outcome.target_distances.assign(scene.bodies().size(), nan);
  outcome.target_yaw_distances.assign(scene.bodies().size(), nan);
  for (size_t b = 0; b < scene.bodies().size(); ++b) {
    const BodyTask& t = task.bodies[b];
    if (t.hasYawTarget()) {
      const double distance = std::fabs(scene.yaw(static_cast<int>(b), end) - t.target_yaw);
      const double tolerance = targetTolerance(t.target_yaw_weight * unit * unit);
      outcome.target_yaw_distances[b] = distance;
      if (distance > tolerance) {
        missed << (missed.tellp() > 0 ? "; " : "") << "body '" << scene.bodies()[b].name
               << "' ends " << distance << " rad from its target yaw (" << t.target_yaw
               << "), tolerance " << tolerance;
      }
    }
    if (!t.hasTarget()) continue;
    const double distance = (scene.position(static_cast<int>(b), end) - t.target).norm();
    outcome.target_distances[b] = distance;
    if (distance <= targetTolerance(t.target_weight)) continue;
    missed << (missed.tellp() > 0 ? "; " : "") << "body '" << scene.bodies()[b].name << "' ends "
           << scene.userLength(distance) << " from its target (" << (unit * t.target).transpose()
           << "), tolerance " << scene.userLength(targetTolerance(t.target_weight));
    for (const PushPlan::ShortPush& push : guess.short_pushes) {
      if (push.body != static_cast<int>(b)) continue;
      missed << (push.time_limited
                     ? " (out of the pushers' reach within the horizon at their speed bounds; "
                       "planned as far towards it as time allows, ("
                     : " (out of the pushers' reach: workspace bounds, obstacles or walls; planned "
                       "to the nearest end they can push it to, (")
             << (unit * push.end).transpose() << "))";
    }
  }
  if (outcome.status == SolveStatus::kSuccess && missed.tellp() > 0) {
    outcome.status = SolveStatus::kTargetNotReached;
    outcome.message = "target not reached: " + missed.str() + "; " + outcome.message;
  }
}

/// Every pair in reach (modelled or checked) measured along the outcome's trajectory, between
/// element boundaries too. After a successful round, the checked pairs that came within the
/// margin become modelled for the next round (named in `rounds_note`); after a failed one those
/// it passes through, so that no plan through a body or wall is answered without a round that
/// models the pair: true when there is one.
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
    const bool near =
        withinMargin(task.scene, decision.pair, decision.min_distance, options.pair_margin);
    if ((outcome.status == SolveStatus::kSuccess && near) ||
        (!interrupted(outcome.status) && decision.min_distance < 0.0)) {
      reason << "modelled from round " << round + 1 << ": came within "
             << task.scene.userLength(decision.min_distance) << " in round " << round;
      decision.modelled = true;
      decision.checked = false;
      added.push_back(task.scene.pairName(decision.pair));
    } else {
      reason << "checked on the solution: never closer than "
             << task.scene.userLength(decision.min_distance) << " (margin "
             << task.scene.userLength(options.pair_margin * task.scene.pairSize(decision.pair))
             << ")";
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

/// Adds `held` to `all` unless it is there.
void addHeld(const PairInterval& held, std::vector<PairInterval>& all) {
  if (std::find(all.begin(), all.end(), held) == all.end()) all.push_back(held);
}

}  // namespace

void holdWhatThePlanBeforeHeld(const SceneOutcome& previous, const SceneTask& task,
                               const OcpOptions& ocp, SceneOutcome& outcome) {
  const PlanStructure now =
      planStructure({}, {}, task.horizon, task.num_intervals, ocp.discretization, 1.0);
  const int done = std::max(0, intervalsDone(previous.structure, now));
  for (const PairInterval& held : previous.held_grazes) {
    if (held.interval >= done) addHeld({held.pair, held.interval - done}, outcome.held_grazes);
  }
  const std::vector<int>& before = previous.structure.interval_elements;
  if (static_cast<int>(before.size()) != done + now.intervals ||
      !std::equal(now.interval_elements.begin(), now.interval_elements.end(),
                  before.begin() + done)) {
    return;
  }
  const int elements_done = std::accumulate(before.begin(), before.begin() + done, 0);
  for (Graze point : previous.guard_points) {
    if (point.interval < done) continue;
    point.interval -= done;
    point.element -= elements_done;
    point.time -= done * task.horizon / task.num_intervals;
    outcome.guard_points.push_back(point);
  }
}

namespace {

/// Holds the grazes: a pair and interval not held yet along its elements, and each graze's
/// deepest point exactly (`points`: a held graze that still cuts in between the guards); false
/// when there is none.
bool holdGrazes(const std::vector<Graze>& grazes, std::vector<PairInterval>& held,
                std::vector<Graze>& points) {
  for (const Graze& graze : grazes) {
    addHeld({graze.pair, graze.interval}, held);
    points.push_back(graze);
  }
  return !grazes.empty();
}

/// Where a held graze's gap is kept in each element of its interval: three points in every gap
/// between consecutive stage nodes (and the start), a quarter, a half and three quarters in.
std::vector<double> guardFractions(const Eigen::VectorXd& nodes) {
  std::vector<double> fractions;
  double previous = 0.0;
  for (int i = 0; i < nodes.size(); ++i) {
    for (double part : {0.25, 0.5, 0.75})
      fractions.push_back(previous + part * (nodes(i) - previous));
    previous = nodes(i);
  }
  return fractions;
}

/// The gap guards of the held grazes and of the points (elements of this grid) whose pairs the
/// part models, on the grid of `grid`.
std::vector<GapGuard> gapGuards(const SceneTask& task, const MovingPart& part,
                                const std::vector<PairInterval>& held,
                                const std::vector<Graze>& points,
                                const DiscretizationOptions& grid) {
  std::vector<GapGuard> guards;
  const auto constraintOf = [&](const ContactPair& pair) {
    const auto found = std::find(part.modelled_in_task.begin(), part.modelled_in_task.end(), pair);
    return found == part.modelled_in_task.end()
               ? -1
               : static_cast<int>(found - part.modelled_in_task.begin());
  };
  std::vector<int> first_element{0};
  OcpOptions options;
  options.discretization = grid;
  for (int count : intervalElements(task, options)) {
    first_element.push_back(first_element.back() + count);
  }
  const std::vector<double> fractions = guardFractions(makeTableau(grid.family, grid.num_stages).c);
  for (const PairInterval& h : held) {
    const int constraint = constraintOf(h.pair);
    if (constraint < 0 || h.interval >= task.num_intervals) continue;
    for (int e = first_element[h.interval]; e < first_element[h.interval + 1]; ++e) {
      for (double fraction : fractions) guards.push_back({e, constraint, fraction});
    }
  }
  // A cut held at its deepest point moves beside it, about 4x shallower (a round each): the
  // points a quarter of the way to the nearest guard on either side are held too.
  const size_t grid_guards = guards.size();
  for (const Graze& point : points) {
    const int constraint = constraintOf(point.pair);
    if (constraint < 0 || !(point.fraction > 0.0 && point.fraction < 1.0)) continue;
    double below = 0.0, above = 1.0;
    for (size_t g = 0; g < grid_guards; ++g) {
      if (guards[g].element != point.element || guards[g].constraint != constraint) continue;
      if (guards[g].fraction < point.fraction) below = std::max(below, guards[g].fraction);
      if (guards[g].fraction > point.fraction) above = std::min(above, guards[g].fraction);
    }
    for (double fraction : {point.fraction - 0.25 * (point.fraction - below), point.fraction,
                            point.fraction + 0.25 * (above - point.fraction)}) {
      guards.push_back({point.element, constraint, fraction});
    }
  }
  return guards;
}

/// The task with the bodies an earlier solve held on their supports (a finer rung's, a
/// replan's) held, and those bodies in `held`.
SceneTask withHeldBodies(const SceneTask& task, const SceneSolveOptions& options,
                         std::vector<int>& held) {
  SceneTask holding = task;
  for (const SceneOutcome* earlier : {options.refine, options.previous}) {
    if (earlier == nullptr) continue;
    for (int b : earlier->held_on_support) {
      if (b >= static_cast<int>(holding.bodies.size())) continue;
      holding.bodies[b].hold_on_support = true;
      if (std::find(held.begin(), held.end(), b) == held.end()) held.push_back(b);
    }
  }
  return holding;
}

/// After a successful round: the supported bodies whose plan would lift them off their support
/// are pushed from the next round only as their support holds them (in `tasks`); true when there
/// is one.
bool holdLiftedBodies(std::vector<SceneTask*> tasks, int round, SceneOutcome& outcome,
                      std::string& rounds_note) {
  const SceneTask& task = *tasks.front();
  const Scene& scene = task.scene;
  const std::vector<double> lifts = supportLifts(task, outcome.trajectory, outcome.modelled);
  bool held = false;
  for (int b = 0; b < static_cast<int>(lifts.size()); ++b) {
    const int wall = scene.supportOf(b);
    if (wall < 0 || task.bodies[b].hold_on_support ||
        !(lifts[b] > kSupportLiftTolerance * boundingRadius(scene.bodies()[b]))) {
      continue;
    }
    std::ostringstream note;
    note.precision(3);
    note << "; a push of round " << round << " would lift '" << scene.bodies()[b].name << "' off '"
         << scene.walls()[wall].name << "' by " << scene.userLength(lifts[b])
         << " (a push from below its centre, which the support cannot hold down): from round "
         << round + 1 << " the plan pushes it only as '" << scene.walls()[wall].name
         << "' holds it";
    rounds_note += note.str();
    for (SceneTask* t : tasks) t->bodies[b].hold_on_support = true;
    outcome.held_on_support.push_back(b);
    held = true;
  }
  return held;
}

}  // namespace

std::string warmStartRefusal(const SceneOutcome& previous, const SceneOutcome& now) {
  return warmStartRefusal(previous.solved() && solvedItsNlp(previous.status),
                          static_cast<int>(previous.report.solution.size()), previous.sizes,
                          previous.structure, now.sizes, now.structure);
}

SceneOutcome solveSceneTask(const SceneTask& task, const TaskLimits& limits,
                            const SceneSolveOptions& options) {
  if (options.length_scaling) {
    return solveInLengthUnits(task, options,
                              [&](const SceneTask& scaled, const SceneSolveOptions& inner) {
                                return solveSceneTask(scaled, limits, inner);
                              });
  }
  Stopwatch stopwatch;
  SceneOutcome outcome;
  // The task as solved: with the bodies that earlier solves found lifted held on their supports.
  SceneTask current = withHeldBodies(task, options, outcome.held_on_support);
  if (!prepare(current, limits, true, outcome)) return outcome;
  if (!options.prune_pairs) {
    for (PairDecision& decision : outcome.decisions) decision.modelled = true;
  }
  const std::vector<ContactPair> candidates = modelledPairs(outcome.decisions);
  const FirstGuess first_guess = firstGuess(current, candidates, options);
  outcome.pusher_sphere = first_guess.pusher_sphere;
  outcome.planned_legs = first_guess.legs;
  outcome.planned_transits = first_guess.transits;
  // A soft target out of the pushers' reach: the OCP aims at the nearest end the plan can push
  // to (a reachable task, solved as fast as one), and the answer is judged by the real target.
  SceneTask aimed = reachableTask(current, first_guess);
  const SceneOutcome* refine = options.refine;
  // The plan the next round starts from, in the full scene, with the pairs of its multipliers.
  Trajectory from_plan;
  std::vector<ContactPair> from_pairs;
  double from_polish_sigma = 0.0, from_sigma = options.ocp.guess_sigma;
  outcome.held_grazes = options.held_grazes;
  if (refine != nullptr) {
    outcome.decisions = refine->decisions;
    from_plan = refinedTrajectory(
        refine->trajectory, intervalElements(task, options.ocp),
        makeTableau(options.ocp.discretization.family, options.ocp.discretization.num_stages).c);
    from_pairs = refine->modelled;
    from_polish_sigma = refine->report.polish_sigma;
    from_sigma = tightestRelaxation(refine->report, options.ocp.guess_sigma);
    for (const PairInterval& held : refine->held_grazes) addHeld(held, outcome.held_grazes);
  } else {
    chooseFirstPairs(aimed, candidates, first_guess, options, outcome);
  }
  if (options.previous != nullptr) {
    holdWhatThePlanBeforeHeld(*options.previous, task, options.ocp, outcome);
  }
  std::string rounds_note;
  bool pairs_added = false;  // the round before added pairs or held bodies (a lazy round follows)
  for (int round = 1;; ++round) {
    const MovingPart part = movingPartOf(aimed, outcome);
    OcpOptions ocp_options = options.ocp;
    if (options.previous != nullptr) {
      ocp_options.homotopy.previous_polish_iterations = kReplanPolishIterations;
      // A replan is one of many: the next one starts from where this plan leads.
      ocp_options.homotopy.accept_unsolved_branch_check = true;
      ocp_options.homotopy.resume_from_unsolved_polish = true;
      // From the plan's point a monotone barrier (free there: cluttered seed 7's closed loop
      // took 8651 replan iterations, not 7526).
      ocp_options.homotopy.ipopt.near_solution_barrier = BarrierStrategy{};
    }
    ocp_options.discretization.gap_guards = gapGuards(
        current, part, outcome.held_grazes, outcome.guard_points, ocp_options.discretization);
    const OcpDefinition ocp = buildOcp(part.task, part.modelled);
    ocp_options.homotopy.wall_time_budget =
        std::max(0.0, options.ocp.homotopy.wall_time_budget - stopwatch.wallSeconds());
    if (pairs_added && !current.scene.hasRobot()) {
      // The previous round's solution is nearly this round's (the new pairs start separated):
      // its homotopy resumes at the tightest relaxation that round reached, not from guess_sigma,
      // but no tighter than 1e-4 (Push-T resuming at 1e-7 took 371 iterations, at 1e-4 168).
      // Same optima on the planning sweep, in less time; a robot's lazy round starts over: on
      // the arm push resuming ended in another local optimum (objective 2.0e-4 against 1.4e-4).
      // Polishing the round before's active set first cost 100 iterations more on 4 of the 16
      // posts scenes at the node's grid and converged on none: the new pairs are the ones it
      // passed too near.
      ocp_options.guess_sigma = std::max(
          kTightestResumedRelaxation, tightestRelaxation(outcome.report, ocp_options.guess_sigma));
    }
    OcpSolver solver(ocp, ocp_options);
    solver.setMonitor(options.monitor);
    const NlpAssembly& nlp = solver.discretization().nlp();
    outcome.sizes = {nlp.numVariables(), nlp.numConstraints(), nlp.numComplementarities()};
    const std::string too_large = nlpTooLarge(nlp, part.modelled.size(), current, options, limits);
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
    if (pairs_added) {
      solution = solver.solve(partTrajectory(aimed, part, from_plan, from_pairs), guess);
    } else if (!from_plan.elements.empty()) {
      solution = solver.solveFromPlan(partTrajectory(aimed, part, from_plan, from_pairs),
                                      from_polish_sigma, from_sigma, guess);
      if (round == 1) {
        outcome.refined_plan = solution.start == OcpStart::kTrajectory;
        outcome.plan_source = "coarser rung's plan";
        if (!outcome.refined_plan) {
          rounds_note += "; from the coarser rung's plan it failed: from the push plan";
        }
      }
    } else if (options.previous != nullptr) {
      const SceneOutcome& previous_outcome = *options.previous;
      outcome.cold_start_reason = warmStartRefusal(previous_outcome, outcome);
      const int done = solvedItsNlp(previous_outcome.status) && previous_outcome.solved()
                           ? intervalsDone(previous_outcome.structure, outcome.structure)
                           : -1;
      if (outcome.cold_start_reason.empty()) {
        OcpSolution previous;
        previous.report = previous_outcome.report;
        solution = solver.solve(previous, guess);
        if (solution.start != OcpStart::kPrevious) {
          outcome.cold_start_reason = "the warm solve failed";
        }
        outcome.warm_started = solution.start == OcpStart::kPrevious;
      } else if (done >= 0) {
        // A replan after `done` intervals of the plan were executed: from the rest of it.
        const Trajectory rest = refinedTrajectory(
            laterPart(previous_outcome.trajectory, done), intervalElements(task, options.ocp),
            makeTableau(options.ocp.discretization.family, options.ocp.discretization.num_stages)
                .c);
        solution = solver.solveFromPlan(
            partTrajectory(aimed, part, rest, previous_outcome.modelled),
            previous_outcome.report.polish_sigma,
            tightestRelaxation(previous_outcome.report, options.ocp.guess_sigma), guess);
        outcome.warm_started = solution.start == OcpStart::kTrajectory;
        outcome.plan_source = "previous plan after " + std::to_string(done) + " interval(s)";
        outcome.cold_start_reason =
            outcome.warm_started ? "" : "the solve from the previous plan failed";
      } else {
        solution = solver.solve(guess);
      }
      outcome.guess_residual = solution.guess_residual;
    } else {
      solution = solver.solve(guess);
      outcome.guess_residual = solution.guess_residual;
    }
    if (round > 1) {
      solution.report.history.insert(solution.report.history.begin(),
                                     outcome.report.history.begin(), outcome.report.history.end());
      solution.report.addEffort(outcome.report);
    }
    outcome.status = solution.status;
    outcome.message = solution.message;
    outcome.start = round == 1 ? solution.start : outcome.start;
    outcome.trajectory = fullSceneTrajectory(aimed, part, solution.trajectory);
    outcome.report = solution.report;
    outcome.pair_rounds = round - outcome.graze_rounds;
    outcome.modelled = part.modelled_in_task;
    // The next round starts from this plan (a graze round: its active set first).
    from_plan = outcome.trajectory;
    from_pairs = part.modelled_in_task;
    from_polish_sigma = solution.report.polish_sigma;
    from_sigma = tightestRelaxation(outcome.report, options.ocp.guess_sigma);
    pairs_added = measureGaps(aimed, options, round - outcome.graze_rounds, outcome, rounds_note);
    if (pairs_added) continue;
    if (outcome.status != SolveStatus::kSuccess) break;
    pairs_added = holdLiftedBodies({&aimed, &current}, round, outcome, rounds_note);
    if (pairs_added) continue;
    outcome.grazes = planGrazes(aimed, outcome.trajectory, outcome.modelled, options.graze_depth);
    if (outcome.graze_rounds >= options.max_graze_rounds ||
        !holdGrazes(outcome.grazes, outcome.held_grazes, outcome.guard_points)) {
      break;
    }
    ++outcome.graze_rounds;
    rounds_note += "; " + describeGrazes(current.scene, outcome.grazes) + ": held in a new round";
  }
  outcome.message += rounds_note;
  if (!outcome.grazes.empty()) {
    outcome.message += "; the plan cuts into a body between stage points: " +
                       describeGrazes(current.scene, outcome.grazes);
  }
  if (!outcome.trajectory.states.empty()) {
    outcome.boundary_gap = smallestBoundaryGap(current.scene, outcome.modelled, outcome.trajectory);
  }
  for (int b = 0; b < static_cast<int>(current.scene.bodies().size()); ++b) {
    outcome.supports.push_back(current.scene.supportOf(b));
  }
  judgeTargets(current, outcome, first_guess);
  if (options.verify && outcome.status != SolveStatus::kCancelled) {
    const SimulationOptions fine =
        verificationOptions(options.verification, options.ocp,
                            options.ocp.homotopy.wall_time_budget - stopwatch.wallSeconds());
    outcome.verification = verifyPlan(current, outcome.trajectory, outcome.decisions, fine,
                                      options.pair_margin, options.graze_depth);
    outcome.verified = true;
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
  const int most =
      solved.interval_elements.empty()
          ? solved.num_elements
          : *std::max_element(solved.interval_elements.begin(), solved.interval_elements.end());
  fine.discretization.num_elements = std::max(fine.discretization.num_elements, 2 * most);
  // 0 when the solve used it all: the re-simulation times out and its error is infinite.
  fine.wall_time_budget = std::max(0.0, remaining_budget);
  fine.refine_by_homotopy = false;
  // A step's relaxed NLP converges in tens of iterations; one that needs more is a step with
  // more switches than element boundaries (a contact and the release it causes), which
  // splitting resolves: on the cluttered family such homotopies ran 300-1200 iterations to fail.
  fine.homotopy.ipopt.max_iterations = kVerificationNlpIterations;
  fine.retry_homotopy.ipopt.max_iterations = kVerificationNlpIterations;
  fine.split_before_homotopy = true;
  // A part that reaches the homotopy holds more switches than its elements place; a failed
  // relaxation there rarely recovers, so each homotopy gives way to its fallback soon: the
  // retry at the first failure, twice the elements and fixed steps after two in a row.
  fine.homotopy.max_consecutive_failures = 1;
  fine.retry_homotopy.max_consecutive_failures = 2;
  return fine;
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
  // In units of the scene's length scale, as a solve (solveInLengthUnits).
  const double length = lengthScale(task);
  const SceneTask scaled = taskInLengthUnits(task, length);
  if (!prepare(scaled, limits, false, outcome)) return outcome;
  const Eigen::VectorXd control_units = solveUnits(scaled.scene).control;
  std::vector<Eigen::VectorXd> scaled_controls;
  for (const Eigen::VectorXd& u : controls) {
    scaled_controls.push_back(u.cwiseQuotient(control_units));
  }
  const MovingPart part = movingPartOf(scaled, outcome);
  const Scene& moving = part.task.scene;
  FesdIntegrator integrator(moving.model(part.modelled), options);
  const SimulationResult result =
      integrator.simulate(moving.initialState(), task.horizon, steps, scaled_controls);
  outcome.modelled = part.modelled_in_task;
  outcome.status = result.status;
  outcome.message = result.message;
  outcome.trajectory = fullSceneTrajectory(scaled, part, result.trajectory);
  outcome.report = result.totals;
  if (options.sensitivities) {
    outcome.sensitivities = fullSceneSensitivities(scaled, part, result.sensitivities);
  }
  for (int b = 0; b < static_cast<int>(scaled.scene.bodies().size()); ++b) {
    outcome.supports.push_back(scaled.scene.supportOf(b));
  }
  outcomeToUserUnits(outcome, solveUnits(scaled.scene));
  outcome.length_scale = length;
  return outcome;
}

}  // namespace fesd
