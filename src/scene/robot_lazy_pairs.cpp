#include "fesd_trajopt/scene/robot_lazy_pairs.h"

#include <algorithm>
#include <limits>

namespace fesd {

double robotPairSize(const RobotScene& scene, const RobotPair& pair) {
  const double radius = scene.collisionBodies().at(pair.body).radius;
  switch (pair.kind) {
    case RobotPair::Kind::kBody:
      return radius + scene.collisionBodies().at(pair.other).radius;
    case RobotPair::Kind::kObstacle:
      return radius + scene.discs().obstacles().at(pair.other).radius;
    case RobotPair::Kind::kWall:
      return radius;
  }
  return radius;
}

bool robotWithinMargin(const RobotScene& scene, const RobotPair& pair, double gap, double margin) {
  return gap < margin * robotPairSize(scene, pair);
}

std::vector<double> smallestPathGaps(const RobotScene& scene, const std::vector<RobotPair>& pairs,
                                     const std::vector<Eigen::VectorXd>& path) {
  std::vector<double> gaps(pairs.size(), std::numeric_limits<double>::infinity());
  for (const Eigen::VectorXd& x : path) {
    const std::vector<double> at = scene.pairGaps(pairs, x);
    for (size_t k = 0; k < pairs.size(); ++k) gaps[k] = std::min(gaps[k], at[k]);
  }
  return gaps;
}

std::vector<bool> robotPairsTheGuessNeeds(const RobotTask& task,
                                          const std::vector<RobotPair>& candidates,
                                          const TrajectoryGuess& guess, double margin,
                                          int samples) {
  std::vector<Eigen::VectorXd> path;
  std::vector<bool> needed(candidates.size(), false);
  for (int i = 0; i <= samples; ++i) {
    const double t = task.horizon * i / samples;
    path.push_back(guess.state(t));
    if (!guess.multipliers) continue;
    const Eigen::VectorXd lambda = guess.multipliers(t);
    for (size_t k = 0; k < candidates.size(); ++k) needed[k] = needed[k] || lambda(k) > 0.0;
  }
  const std::vector<double> gaps = smallestPathGaps(task.scene, candidates, path);
  for (size_t k = 0; k < candidates.size(); ++k) {
    needed[k] = needed[k] || robotWithinMargin(task.scene, candidates[k], gaps[k], margin);
  }
  return needed;
}

Trajectory trajectoryForPairs(const Trajectory& trajectory, const std::vector<RobotPair>& from,
                              const std::vector<RobotPair>& to) {
  Trajectory result = trajectory;
  result.switches.clear();
  result.unresolved_switches.clear();
  for (ElementValues& element : result.elements) {
    const Eigen::Index stages = element.stage_states.cols();
    Eigen::MatrixXd multipliers = Eigen::MatrixXd::Zero(to.size(), stages);
    for (size_t k = 0; k < to.size(); ++k) {
      const auto found = std::find(from.begin(), from.end(), to[k]);
      if (found != from.end()) {
        multipliers.row(k) = element.stage_multipliers.row(found - from.begin());
      }
    }
    element.stage_multipliers = multipliers;
    element.stage_constraints = Eigen::MatrixXd::Zero(to.size(), stages);
    element.lowest_constraints.resize(0);
  }
  return result;
}

}  // namespace fesd
