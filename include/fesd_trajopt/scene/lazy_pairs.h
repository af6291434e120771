#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/discretization/trajectory_guess.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// The smallest gap of each pair along a path of states of the task's scene (smallestGap).
std::vector<double> smallestGaps(const DiscScene& scene, const std::vector<ContactPair>& pairs,
                                 const std::vector<Eigen::VectorXd>& path);

/// A pair's gap compared with its margin: closer than `margin` times pairSize.
bool withinMargin(const DiscScene& scene, const ContactPair& pair, double gap, double margin);

/// Which of `candidates` (the pairs in reach) a solve models first: those the first guess
/// presses on (a multiplier > 0, the guess's multipliers being the candidates') and those it
/// brings within the margin of contact, along `samples` + 1 states evenly spread over the
/// horizon. One flag per candidate, and why.
struct PairSelection {
  std::vector<bool> modelled;
  std::vector<std::string> reasons;
};
PairSelection pairsTheGuessNeeds(const SceneTask& task, const std::vector<ContactPair>& candidates,
                                 const TrajectoryGuess& guess, double margin, int samples);

}  // namespace fesd
