#pragma once

#include <vector>

#include "fesd_trajopt/discretization/trajectory_guess.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// The push planner plans discs: a task without a robot whose free bodies carry several spheres
/// (or turn) is planned as the task of their bounding discs, and the plan is mapped back.
bool hasCompositeBodies(const Scene& scene);

/// Each free body as one disc about its position that holds its spheres, not turning; the same
/// body indices, obstacles and body tasks (without yaw targets); in the plane each wall moved
/// back by the most a body of spheres gets nearer to it than its disc, at its target yaw (else
/// its start yaw), so that a box can be planned into a corner.
SceneTask boundingDiscTask(const SceneTask& task);

/// A pair of the task's collision bodies as the pair of their bodies' discs in boundingDiscTask.
ContactPair boundingDiscPair(const Scene& scene, const ContactPair& pair);

/// A guess of the bounding discs' task as one of the task's: positions from the discs' states (a
/// turning body keeps its start yaw), controls as they are, and each disc pair's multiplier
/// (disc_pairs, the disc task's list) on the pair of `pairs` that stands for it (disc_of) whose
/// gap is the smallest at that time.
TrajectoryGuess guessOfSpheres(const SceneTask& task, const std::vector<ContactPair>& pairs,
                               const std::vector<int>& disc_of, int disc_pair_count,
                               const TrajectoryGuess& disc_guess);

}  // namespace fesd
