#pragma once

#include <limits>
#include <string>
#include <vector>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/scene/robot_task.h"

namespace fesd {

struct RobotSolveOptions {
  OcpOptions ocp;
  /// Re-simulate the optimal controls on a finer grid (at least the solve's stages, twice its
  /// elements) with the same pairs and report the end state's deviation and the smallest gap.
  bool verify = true;
  DiscretizationOptions verification;
};

/// A robot task planned: the pair decisions, the first guess's pushing sphere, the solution and
/// its checks. A refused task (`invalid`) is not solved.
struct RobotOutcome {
  std::string invalid;
  std::vector<RobotPairDecision> decisions;
  std::vector<RobotPair> modelled;  ///< the NLP's constraints, in order
  int pusher_sphere = -1;
  SolveStatus status = SolveStatus::kSolverError;
  std::string message;
  Trajectory trajectory;
  MpccReport report;
  /// The smallest gap of the modelled pairs at the element boundaries (negative: penetration).
  double boundary_gap = std::numeric_limits<double>::quiet_NaN();
  double verification_error = std::numeric_limits<double>::quiet_NaN();
  /// The smallest gap of the modelled pairs at the verification's element boundaries.
  double verification_gap = std::numeric_limits<double>::quiet_NaN();
  /// Per free body: its end position's distance from its target (NaN without one).
  std::vector<double> target_distances;
  /// Per joint: |q_j(T) - target| (NaN without a target).
  std::vector<double> joint_target_distances;
};

/// validateRobotTask, decideRobotPairs (every pair in reach is modelled), planRobotGuess, one
/// OcpSolver solve from the guess, the targets judged (a success that misses a weighted target by
/// more than targetTolerance is kTargetNotReached) and, on request, the verification.
RobotOutcome solveRobotTask(const RobotTask& task, const TaskLimits& limits,
                            const RobotSolveOptions& options);

/// The smallest gap of `pairs` over the states at the trajectory's element boundaries.
double smallestBoundaryGap(const RobotScene& scene, const std::vector<RobotPair>& pairs,
                           const Trajectory& trajectory);

}  // namespace fesd
