#pragma once

#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/discretization/trajectory.h"
#include "fesd_trajopt/discretization/trajectory_guess.h"
#include "fesd_trajopt/scene/robot_task.h"

namespace fesd {

/// The length a robot pair's margin is relative to: the sum of its radii (a wall pair: the
/// body's radius), as pairSize for discs.
double robotPairSize(const RobotScene& scene, const RobotPair& pair);
/// Whether a gap of the pair is within margin * robotPairSize (the lazy pairs' test).
bool robotWithinMargin(const RobotScene& scene, const RobotPair& pair, double gap, double margin);

/// The smallest gap of each pair over the states of a path. A robot sphere moves on arcs, so
/// unlike smallestGap this only samples: pass a dense path (densePath).
std::vector<double> smallestPathGaps(const RobotScene& scene, const std::vector<RobotPair>& pairs,
                                     const std::vector<Eigen::VectorXd>& path);

/// Which of `candidates` a first solve models, as pairsTheGuessNeeds for discs: those the guess
/// presses on (a multiplier > 0, its multipliers being the candidates') and those it brings within
/// margin * robotPairSize, along samples + 1 states evenly spread over the horizon.
std::vector<bool> robotPairsTheGuessNeeds(const RobotTask& task,
                                          const std::vector<RobotPair>& candidates,
                                          const TrajectoryGuess& guess, double margin, int samples);

/// A solution whose multipliers belong to `from` as a start for a solve with the pairs `to`: each
/// pair's multipliers where `from` has it, 0 otherwise; constraint values left 0, switches cleared.
Trajectory trajectoryForPairs(const Trajectory& trajectory, const std::vector<RobotPair>& from,
                              const std::vector<RobotPair>& to);

}  // namespace fesd
