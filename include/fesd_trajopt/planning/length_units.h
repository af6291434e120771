#pragma once

#include <functional>
#include <vector>

#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/scene_units.h"

namespace fesd {

/// A trajectory of a solve, whose multipliers' rows are `pairs`, in the user's units: states,
/// stage states and controls times their units; a pair of spheres' constraint values times L^2
/// and its multipliers unchanged (a wall's, whose c is linear: both times L); the lowest
/// constraints (distances) times L; times unchanged.
void scaleTrajectory(Trajectory& trajectory, const std::vector<ContactPair>& pairs,
                     const SolveUnits& units);

/// An outcome of a solve in the user's units: every length, state, control, force and distance as
/// scaleTrajectory, the objective (and each homotopy step's) times L^2, sensitivities by their
/// coordinates' units, the verification's errors and gaps times L (a state's norm in the solve's
/// metric, a revolute joint's motion as an arc at the robot's reach). The report's residuals,
/// relaxations and NLP point stay the solve's (its tolerances are in its units); messages are
/// written in the user's units already (Scene::length_unit).
void outcomeToUserUnits(SceneOutcome& outcome, const SolveUnits& units);
/// The inverse: an outcome in the user's units in the solve's (a warm start's, a rung's).
void outcomeToSolveUnits(SceneOutcome& outcome, const SolveUnits& units);

/// A solve in units of the task's lengthScale: `solve` (with length_scaling off) gets
/// taskInLengthUnits and the options' previous and refine outcomes in those units, and the
/// outcome comes back in the task's; the options' monitor hears each step's objective in the
/// task's units. The solve validates the scaled task (its limits in units of the length scale,
/// its messages in the task's units: Scene::length_unit).
SceneOutcome solveInLengthUnits(
    const SceneTask& task, const SceneSolveOptions& options,
    const std::function<SceneOutcome(const SceneTask&, const SceneSolveOptions&)>& solve);

}  // namespace fesd
