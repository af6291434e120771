#include "fesd_trajopt/scene/moving_part.h"

#include <algorithm>
#include <limits>

namespace fesd {
namespace {

/// Whether a pair has a collision body of free body `body` on either side.
bool involves(const std::vector<CollisionBody>& bodies, const ContactPair& pair, int body) {
  return bodies[pair.body].free_body == body ||
         (pair.kind == ContactPair::Kind::kBody && bodies[pair.other].free_body == body);
}

/// A state of the full scene: the joints and moving bodies from `moving`, the frozen bodies at
/// their start.
Eigen::VectorXd fullState(const SceneTask& full, const MovingPart& part,
                          const Eigen::VectorXd& moving) {
  Eigen::VectorXd state = full.scene.initialState();
  state.head(full.scene.numJoints()) = moving.head(full.scene.numJoints());
  for (size_t i = 0; i < part.bodies.size(); ++i) {
    const int body = part.bodies[i];
    state.segment(full.scene.stateIndex(body), full.scene.coordinates(body)) = moving.segment(
        part.task.scene.stateIndex(static_cast<int>(i)), full.scene.coordinates(body));
  }
  return state;
}

/// Per state component of the part, its index in the full scene's state.
std::vector<int> fullStateIndices(const SceneTask& full, const MovingPart& part) {
  std::vector<int> indices;
  for (int j = 0; j < full.scene.numJoints(); ++j) indices.push_back(j);
  for (const int body : part.bodies) {
    for (int d = 0; d < full.scene.coordinates(body); ++d) {
      indices.push_back(full.scene.stateIndex(body) + d);
    }
  }
  return indices;
}

/// Per modelled pair of the part, its index in `pairs`, or -1.
std::vector<int> pairSources(const MovingPart& part, const std::vector<ContactPair>& pairs) {
  std::vector<int> sources;
  for (const ContactPair& pair : part.modelled_in_task) {
    const auto found = std::find(pairs.begin(), pairs.end(), pair);
    sources.push_back(found == pairs.end() ? -1 : static_cast<int>(found - pairs.begin()));
  }
  return sources;
}

/// The rows of `values` (one per pair of `pairs`) that the part's modelled pairs take.
Eigen::MatrixXd pairRows(const std::vector<int>& sources, const Eigen::MatrixXd& values) {
  Eigen::MatrixXd rows = Eigen::MatrixXd::Zero(sources.size(), values.cols());
  for (size_t k = 0; k < sources.size(); ++k) {
    if (sources[k] >= 0) rows.row(k) = values.row(sources[k]);
  }
  return rows;
}

}  // namespace

Eigen::VectorXd partState(const SceneTask& full, const MovingPart& part,
                          const Eigen::VectorXd& state) {
  Eigen::VectorXd moving(part.task.scene.stateSize());
  moving.head(full.scene.numJoints()) = state.head(full.scene.numJoints());
  for (size_t i = 0; i < part.bodies.size(); ++i) {
    const int body = part.bodies[i];
    moving.segment(part.task.scene.stateIndex(static_cast<int>(i)), full.scene.coordinates(body)) =
        state.segment(full.scene.stateIndex(body), full.scene.coordinates(body));
  }
  return moving;
}

MovingPart movingPart(const SceneTask& task, const std::vector<PairDecision>& decisions) {
  std::vector<ContactPair> modelled;
  for (const PairDecision& d : decisions) {
    if (d.modelled) modelled.push_back(d.pair);
  }
  const std::vector<CollisionBody> bodies = task.scene.collisionBodies();
  MovingPart part;
  part.task = task;
  part.task.scene.bodies().clear();
  part.task.bodies.clear();
  part.task.allowed_pairs.clear();
  for (int b = 0; b < static_cast<int>(task.scene.bodies().size()); ++b) {
    const bool moves = task.scene.bodies()[b].actuated ||
                       std::any_of(modelled.begin(), modelled.end(),
                                   [&](const ContactPair& p) { return involves(bodies, p, b); });
    if (!moves) continue;
    part.bodies.push_back(b);
    part.task.scene.bodies().push_back(task.scene.bodies()[b]);
    part.task.bodies.push_back(task.bodies[b]);
  }
  // The part keeps the order of bodies and spheres: a moving body's collision bodies come next.
  std::vector<int> new_index(bodies.size(), -1);
  int next_free = 0;
  for (size_t i = 0; i < bodies.size(); ++i) {
    if (bodies[i].sphere >= 0) {
      new_index[i] = part.task.scene.sphereBody(bodies[i].sphere);
    } else if (std::count(part.bodies.begin(), part.bodies.end(), bodies[i].free_body)) {
      new_index[i] = next_free++;
    }
  }
  part.modelled_in_task = modelled;
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

SimulationSensitivities fullSceneSensitivities(const SceneTask& full, const MovingPart& part,
                                               const SimulationSensitivities& sensitivities) {
  const std::vector<int> indices = fullStateIndices(full, part);
  const int nx = full.scene.stateSize(), part_nx = static_cast<int>(indices.size());
  constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  // Rows of d(part) / d(part start, controls) as rows over (full start, controls); an undefined
  // (NaN) block stays wholly NaN.
  const auto widen = [&](const Eigen::MatrixXd& rows) -> Eigen::MatrixXd {
    const int controls = static_cast<int>(rows.cols()) - part_nx;
    if (!rows.allFinite()) return Eigen::MatrixXd::Constant(rows.rows(), nx + controls, kNaN);
    Eigen::MatrixXd wide = Eigen::MatrixXd::Zero(rows.rows(), nx + controls);
    for (int j = 0; j < part_nx; ++j) wide.col(indices[j]) = rows.col(j);
    wide.rightCols(controls) = rows.rightCols(controls);
    return wide;
  };
  SimulationSensitivities result = sensitivities;
  for (Eigen::MatrixXd& state : result.states) {
    const Eigen::MatrixXd wide = widen(state);
    if (!wide.allFinite()) {
      state = Eigen::MatrixXd::Constant(nx, wide.cols(), kNaN);
      continue;
    }
    state = Eigen::MatrixXd::Zero(nx, wide.cols());
    state.leftCols(nx).setIdentity();  // a frozen body: its own start
    for (int i = 0; i < part_nx; ++i) state.row(indices[i]) = wide.row(i);
  }
  for (Eigen::RowVectorXd& row : result.switch_times) row = widen(row);
  return result;
}

TrajectoryGuess partGuess(const SceneTask& full, const MovingPart& part,
                          const TrajectoryGuess& guess, const std::vector<ContactPair>& pairs) {
  TrajectoryGuess result;
  result.controls = guess.controls;
  result.state = [full, part, state = guess.state](double t) {
    return partState(full, part, state(t));
  };
  if (guess.multipliers) {
    result.multipliers = [sources = pairSources(part, pairs),
                          multipliers = guess.multipliers](double t) -> Eigen::VectorXd {
      return pairRows(sources, multipliers(t));
    };
  }
  return result;
}

Trajectory partTrajectory(const SceneTask& full, const MovingPart& part,
                          const Trajectory& trajectory, const std::vector<ContactPair>& pairs) {
  const std::vector<int> sources = pairSources(part, pairs);
  Trajectory result = trajectory;
  result.switches.clear();
  result.unresolved_switches.clear();
  for (Eigen::VectorXd& x : result.states) x = partState(full, part, x);
  for (ElementValues& element : result.elements) {
    Eigen::MatrixXd stages(part.task.scene.stateSize(), element.stage_states.cols());
    for (int j = 0; j < stages.cols(); ++j) {
      stages.col(j) = partState(full, part, element.stage_states.col(j));
    }
    element.stage_states = stages;
    element.stage_multipliers = pairRows(sources, element.stage_multipliers);
    element.stage_constraints = Eigen::MatrixXd::Zero(sources.size(), stages.cols());
    element.lowest_constraints.resize(0);
  }
  return result;
}

}  // namespace fesd
