#include "fesd_trajopt/scene/lazy_pairs.h"

#include <sstream>

#include "fesd_trajopt/scene/pair_check.h"

namespace fesd {

PairSelection pairsTheGuessNeeds(const Scene& scene, double horizon,
                                 const std::vector<ContactPair>& candidates,
                                 const TrajectoryGuess& guess, double margin, int samples) {
  std::vector<Eigen::VectorXd> path;
  std::vector<bool> pressed(candidates.size(), false);
  for (int i = 0; i <= samples; ++i) {
    const double t = horizon * i / samples;
    path.push_back(guess.state(t));
    if (!guess.multipliers) continue;
    const Eigen::VectorXd lambda = guess.multipliers(t);
    for (size_t k = 0; k < candidates.size(); ++k) pressed[k] = pressed[k] || lambda(k) > 0.0;
  }
  const std::vector<double> gaps = smallestGaps(scene, candidates, path);
  PairSelection selection;
  for (size_t k = 0; k < candidates.size(); ++k) {
    std::ostringstream reason;
    reason.precision(3);
    const bool close = withinMargin(scene, candidates[k], gaps[k], margin);
    if (pressed[k]) {
      reason << "in contact in the first guess";
    } else if (close) {
      reason << "within the margin in the first guess (gap " << scene.userLength(gaps[k]) << ")";
    }
    selection.modelled.push_back(pressed[k] || close);
    selection.reasons.push_back(reason.str());
  }
  return selection;
}

}  // namespace fesd
