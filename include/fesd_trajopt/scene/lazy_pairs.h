#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/discretization/trajectory_guess.h"
#include "fesd_trajopt/scene/scene.h"

namespace fesd {

/// Which of `candidates` (the pairs in reach) a solve models first: those the first guess
/// presses on (a multiplier > 0, the guess's multipliers being the candidates') and those it
/// brings within the margin of contact (withinMargin), along `samples` + 1 states evenly spread
/// over the horizon. One flag per candidate, and why.
struct PairSelection {
  std::vector<bool> modelled;
  std::vector<std::string> reasons;
};
PairSelection pairsTheGuessNeeds(const Scene& scene, double horizon,
                                 const std::vector<ContactPair>& candidates,
                                 const TrajectoryGuess& guess, double margin, int samples);

}  // namespace fesd
