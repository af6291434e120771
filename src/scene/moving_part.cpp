#include "fesd_trajopt/scene/moving_part.h"

#include <algorithm>

namespace fesd {
namespace {

bool involves(const ContactPair& pair, int body) {
  return pair.body == body || (pair.kind == ContactPair::Kind::kBody && pair.other == body);
}

/// A state of the full scene: the frozen bodies at their start, the moving ones from `moving`.
Eigen::VectorXd fullState(const SceneTask& full, const MovingPart& part,
                          const Eigen::VectorXd& moving) {
  const int dim = full.scene.dimension();
  Eigen::VectorXd state = full.scene.initialState();
  for (size_t i = 0; i < part.bodies.size(); ++i) {
    state.segment(full.scene.stateIndex(part.bodies[i]), dim) =
        moving.segment(part.task.scene.stateIndex(static_cast<int>(i)), dim);
  }
  return state;
}

}  // namespace

MovingPart movingPart(const SceneTask& task, const std::vector<PairDecision>& decisions) {
  std::vector<ContactPair> modelled;
  for (const PairDecision& d : decisions) {
    if (d.modelled) modelled.push_back(d.pair);
  }
  MovingPart part;
  part.task = task;
  part.task.scene.bodies().clear();
  part.task.bodies.clear();
  part.task.allowed_pairs.clear();
  std::vector<int> new_index(task.scene.bodies().size(), -1);
  for (int b = 0; b < static_cast<int>(task.scene.bodies().size()); ++b) {
    const bool moves = task.scene.bodies()[b].actuated ||
                       std::any_of(modelled.begin(), modelled.end(),
                                   [&](const ContactPair& p) { return involves(p, b); });
    if (!moves) continue;
    new_index[b] = static_cast<int>(part.bodies.size());
    part.bodies.push_back(b);
    part.task.scene.bodies().push_back(task.scene.bodies()[b]);
    part.task.bodies.push_back(task.bodies[b]);
  }
  for (ContactPair pair : modelled) {
    pair.body = new_index[pair.body];
    if (pair.kind == ContactPair::Kind::kBody) pair.other = new_index[pair.other];
    part.modelled.push_back(pair);
  }
  return part;
}

Trajectory fullSceneTrajectory(const SceneTask& full, const MovingPart& part,
                               const Trajectory& trajectory) {
  Trajectory result = trajectory;
  for (Eigen::VectorXd& x : result.states) x = fullState(full, part, x);
  for (ElementValues& element : result.elements) {
    Eigen::MatrixXd stages(full.scene.stateSize(), element.stage_states.cols());
    for (int j = 0; j < stages.cols(); ++j) {
      stages.col(j) = fullState(full, part, element.stage_states.col(j));
    }
    element.stage_states = stages;
  }
  return result;
}

}  // namespace fesd
