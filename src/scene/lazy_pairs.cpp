#include "fesd_trajopt/scene/lazy_pairs.h"

#include <sstream>

#include "fesd_trajopt/scene/pair_check.h"

namespace fesd {

std::vector<double> smallestGaps(const DiscScene& scene, const std::vector<ContactPair>& pairs,
                                 const std::vector<Eigen::VectorXd>& path) {
  std::vector<double> gaps;
  for (const ContactPair& pair : pairs) gaps.push_back(smallestGap(scene, pair, path));
  return gaps;
}

bool withinMargin(const DiscScene& scene, const ContactPair& pair, double gap, double margin) {
  return gap < margin * pairSize(scene, pair);
}

PairSelection pairsTheGuessNeeds(const SceneTask& task, const std::vector<ContactPair>& candidates,
                                 const TrajectoryGuess& guess, double margin, int samples) {
  std::vector<Eigen::VectorXd> path;
  std::vector<bool> pressed(candidates.size(), false);
  for (int i = 0; i <= samples; ++i) {
    const double t = task.horizon * i / samples;
    path.push_back(guess.state(t));
    if (!guess.multipliers) continue;
    const Eigen::VectorXd lambda = guess.multipliers(t);
    for (size_t k = 0; k < candidates.size(); ++k) pressed[k] = pressed[k] || lambda(k) > 0.0;
  }
  const std::vector<double> gaps = smallestGaps(task.scene, candidates, path);
  PairSelection selection;
  for (size_t k = 0; k < candidates.size(); ++k) {
    std::ostringstream reason;
    reason.precision(3);
    const bool close = withinMargin(task.scene, candidates[k], gaps[k], margin);
    if (pressed[k]) {
      reason << "in contact in the first guess";
    } else if (close) {
      reason << "within the margin in the first guess (gap " << gaps[k] << ")";
    }
    selection.modelled.push_back(pressed[k] || close);
    selection.reasons.push_back(reason.str());
  }
  return selection;
}

}  // namespace fesd
