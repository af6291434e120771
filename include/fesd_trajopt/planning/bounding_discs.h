#pragma once

#include <vector>

#include "fesd_trajopt/discretization/trajectory_guess.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// The push planner plans discs: a task without a robot whose free bodies carry several spheres
/// (or turn) is planned as the task of their bounding discs, and the plan is mapped back.
bool hasCompositeBodies(const Scene& scene);

/// A body as one disc about its position that holds its spheres, not turning.
SceneBody boundingDisc(SceneBody body);

/// Each free body as one disc about its position that holds its spheres, not turning; the same
/// body indices, obstacles and body tasks (without yaw targets); in the plane each wall moved
/// back by the most a body of spheres gets nearer to it than its disc, at its target yaw (else
/// its start yaw), so that a box can be planned into a corner.
SceneTask boundingDiscTask(const SceneTask& task);

/// Pairs of the task's collision bodies as pairs of their bodies' discs in boundingDiscTask:
/// each distinct disc pair once (`pairs`, in order of first appearance) and, per pair given, the
/// index of its disc pair (`disc_of`).
struct BoundingDiscPairs {
  std::vector<ContactPair> pairs;
  std::vector<int> disc_of;
};
BoundingDiscPairs boundingDiscPairs(const Scene& scene, const std::vector<ContactPair>& pairs);

/// A guess of the bounding discs' task as one of the task's: positions from the discs' states (a
/// turning body keeps its start yaw), controls as they are, and each disc pair's multiplier on
/// the pair of `pairs` that stands for it (discs.disc_of) whose gap is the smallest at that time.
TrajectoryGuess guessOfSpheres(const SceneTask& task, const std::vector<ContactPair>& pairs,
                               const BoundingDiscPairs& discs, const TrajectoryGuess& disc_guess);

}  // namespace fesd
