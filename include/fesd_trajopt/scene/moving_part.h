#pragma once

#include <vector>

#include "fesd_trajopt/discretization/trajectory.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// The part of a task that can move. A passive body in no modelled pair never moves (its
/// velocity is the projection of f = 0), so it is left out of the optimisation altogether:
/// no states, no dynamics, no constraints; only its constant position is reported.
struct MovingPart {
  SceneTask task;                     ///< the moving bodies only; obstacles and walls as given
  std::vector<int> bodies;            ///< their indices in the full task, in order
  std::vector<ContactPair> modelled;  ///< the modelled pairs in the same order, re-indexed
};

/// Splits off the moving part of a task given its pair decisions (decidePairs). Actuated bodies
/// always move; the order of bodies, controls and modelled pairs is kept.
MovingPart movingPart(const SceneTask& task, const std::vector<PairDecision>& decisions);

/// A trajectory of the moving part as one of the full scene: frozen bodies keep their initial
/// positions in every state and stage state; controls, multipliers and switches are unchanged.
Trajectory fullSceneTrajectory(const SceneTask& full, const MovingPart& part,
                               const Trajectory& trajectory);

}  // namespace fesd
