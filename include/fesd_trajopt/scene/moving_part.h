#pragma once

#include <vector>

#include "fesd_trajopt/discretization/trajectory.h"
#include "fesd_trajopt/discretization/trajectory_guess.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// The part of a task that can move. A passive body in no modelled pair never moves (its
/// velocity is the projection of f = 0), so it is left out of the optimisation altogether:
/// no states, no dynamics, no constraints; only its constant position is reported.
struct MovingPart {
  SceneTask task;           ///< the robot and the moving bodies only; obstacles and walls as given
  std::vector<int> bodies;  ///< their indices in the full task, in order
  std::vector<ContactPair> modelled;          ///< the modelled pairs in the same order, re-indexed
  std::vector<ContactPair> modelled_in_task;  ///< the same pairs with the full task's indices
};

/// Splits off the moving part of a task given its pair decisions (decidePairs). Actuated bodies
/// always move; the order of bodies, controls and modelled pairs is kept.
MovingPart movingPart(const SceneTask& task, const std::vector<PairDecision>& decisions);

/// A state of the moving part: the joints and its bodies' positions in a full scene state.
Eigen::VectorXd partState(const SceneTask& full, const MovingPart& part,
                          const Eigen::VectorXd& state);

/// A trajectory of the moving part as one of the full scene: frozen bodies keep their initial
/// positions in every state and stage state; controls, multipliers and switches are unchanged.
Trajectory fullSceneTrajectory(const SceneTask& full, const MovingPart& part,
                               const Trajectory& trajectory);

/// The sensitivities of a simulation of the moving part as those of the full scene: a frozen body
/// stays where it starts, whatever the others do (its own start: identity; the rest: zero).
SimulationSensitivities fullSceneSensitivities(const SceneTask& full, const MovingPart& part,
                                               const SimulationSensitivities& sensitivities);

/// The moving part's view of a guess for the full task whose multipliers belong to `pairs`
/// (full task indices): the part's states, and each modelled pair's multiplier (0 for a pair
/// that `pairs` lacks).
TrajectoryGuess partGuess(const SceneTask& full, const MovingPart& part,
                          const TrajectoryGuess& guess, const std::vector<ContactPair>& pairs);

/// The moving part's view of a trajectory of the full scene whose multipliers belong to `pairs`
/// (e.g. a solution with fewer modelled pairs): states, stage states and each modelled pair's
/// multipliers (0 for a pair that `pairs` lacks); stage constraint values are left out (0).
Trajectory partTrajectory(const SceneTask& full, const MovingPart& part,
                          const Trajectory& trajectory, const std::vector<ContactPair>& pairs);

}  // namespace fesd
