#pragma once

#include <limits>
#include <string>
#include <vector>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/scene/accuracy_ladder.h"
#include "fesd_trajopt/scene/robot_task.h"
#include "fesd_trajopt/scene/warm_start.h"

namespace fesd {

struct RobotOutcome;

struct RobotSolveOptions {
  OcpOptions ocp;
  /// Lazy pairs, as for discs: model first the pairs in reach that the first guess calls for
  /// (robotPairsTheGuessNeeds), check the others on the solution's dense path, add those within
  /// the margin and solve again from that solution until none is; a warm start's first round
  /// models the pairs the previous plan ended with (all still in reach). Off by default: on the arm
  /// push it ended with 2 of 9 pairs in another local optimum (two hand spheres on the disc in
  /// the last interval) that its re-simulation misses by 6e-2, against 3e-5 with all pairs.
  bool lazy_pairs = false;
  /// With lazy_pairs, a task with at most this many pairs in reach models them all anyway (few
  /// pairs are cheap, and lazy rounds can end in other local optima, as on the arm push).
  int all_pairs_up_to = 0;
  double pair_margin = 0.1;  ///< relative to robotPairSize
  /// Re-simulate the optimal controls on a finer grid (at least the solve's stages, twice its
  /// elements) with every pair in reach that comes within pair_margin along the plan or the
  /// re-simulation (added until none more does) and report the end state's deviation and the
  /// smallest gap of every pair in reach.
  bool verify = true;
  DiscretizationOptions verification;
  const SolveMonitor* monitor = nullptr;  ///< progress and cancel of the solve; not owned
  /// Warm start from this outcome of an earlier solve when warmStartRefusal allows it (the
  /// first round starts from its solution; if that solve fails, from the guess); nullptr:
  /// cold. Not owned.
  const RobotOutcome* previous = nullptr;
};

/// A robot task planned: the pair decisions, the first guess's pushing sphere, the solution and
/// its checks. A refused task (`invalid`) is not solved.
struct RobotOutcome {
  std::string invalid;
  std::vector<RobotPairDecision> decisions;
  std::vector<RobotPair> modelled;  ///< the last NLP's constraints, in order
  int pair_rounds = 0;              ///< solves with a growing set of modelled pairs
  int pusher_sphere = -1;
  SolveStatus status = SolveStatus::kSolverError;
  std::string message;
  Trajectory trajectory;
  MpccReport report;
  /// The smallest gap of the modelled pairs at the element boundaries (negative: penetration).
  double boundary_gap = std::numeric_limits<double>::quiet_NaN();
  double verification_error = std::numeric_limits<double>::quiet_NaN();
  /// The smallest gap of every pair in reach at the verification's element boundaries.
  double verification_gap = std::numeric_limits<double>::quiet_NaN();
  /// Per free body: its end position's distance from its target (NaN without one).
  std::vector<double> target_distances;
  /// Per joint: |q_j(T) - target| (NaN without a target).
  std::vector<double> joint_target_distances;
  std::vector<AccuracyRung> refinements;  ///< solveRobotToAccuracy's rungs, in order
  OcpStart start = OcpStart::kGuess;      ///< where the last round's solve started
  NlpSizes sizes;                         ///< of the last round's NLP
  PlanStructure structure;                ///< of the last round: what a warm start needs
  /// A warm start was asked for but the solve started cold (or fell back to cold): why.
  std::string cold_start_reason;
  /// The first round started from `previous` (later lazy-pair rounds start from the round
  /// before, so `start` alone does not tell).
  bool warm_started = false;
};

/// validateRobotTask, decideRobotPairs, planRobotGuess, rounds of OcpSolver solves over the
/// modelled pairs (lazy pairs: the first from the guess or options.previous, each later one from
/// the round before),
/// the targets judged (a success that misses a weighted target by
/// more than targetTolerance is kTargetNotReached) and, on request, the verification.
RobotOutcome solveRobotTask(const RobotTask& task, const TaskLimits& limits,
                            const RobotSolveOptions& options);

/// The accuracy ladder (climbAccuracyLadder) of a robot task, as solveToAccuracy for discs (a
/// warm start starts on the previous plan's rung).
RobotOutcome solveRobotToAccuracy(const RobotTask& task, const TaskLimits& limits,
                                  RobotSolveOptions options, double target_accuracy);

/// The smallest gap of `pairs` over the states at the trajectory's element boundaries.
double smallestBoundaryGap(const RobotScene& scene, const std::vector<RobotPair>& pairs,
                           const Trajectory& trajectory);

}  // namespace fesd
