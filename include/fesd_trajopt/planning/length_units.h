#pragma once

#include <functional>
#include <vector>

#include "fesd_trajopt/planning/scene_solver.h"

namespace fesd {

/// A trajectory whose multipliers' rows are `pairs` in other length units: states, stage states
/// and controls times `factor`; a pair's constraint values times factor^2 and its multipliers
/// unchanged (a wall's, whose c is linear: both times factor); the lowest constraints (distances)
/// times factor; times unchanged.
void scaleTrajectory(Trajectory& trajectory, const std::vector<ContactPair>& pairs, double factor);

/// An outcome in other length units: every length, state, control, force and distance as
/// scaleTrajectory, the objective (and each homotopy step's) times factor^2, switch times'
/// sensitivities divided by factor. The report's residuals, relaxations and NLP point stay the
/// solve's (its tolerances are in its units); messages are written in the user's units already
/// (Scene::length_unit).
void scaleOutcome(SceneOutcome& outcome, double factor);

/// A solve in units of the task's lengthScale: `solve` (with length_scaling off) gets
/// taskInLengthUnits and the options' previous and refine outcomes in those units, and the
/// outcome comes back in the task's; the options' monitor hears each step's objective in the
/// task's units. A task validateTask or infeasibility refuses is refused in its own units, before
/// it is scaled.
SceneOutcome solveInLengthUnits(
    const SceneTask& task, const TaskLimits& limits, SceneSolveOptions options,
    const std::function<SceneOutcome(const SceneTask&, const SceneSolveOptions&)>& solve);

}  // namespace fesd
