#pragma once

#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/scene_task.h"

/// Small pushing tasks shared by the scene tests.
namespace fesd_test {

/// A pusher at (-3, 0), a puck at the origin (both R = 0.5) and a rock (R = 1) at (100, 100)
/// that nothing reaches in T = 2 at speed 2.
fesd::SceneTask pushingTask();

/// pushingTask with a post (R = 0.4) at (0, 3), which the pusher and the puck can reach.
fesd::SceneTask pushingTaskWithPost();

/// A pusher (R = 0.5) at (-3, 0) with |u| <= 1 per coordinate, a puck at the origin, T = 2:
/// both can get at most D = T sqrt(2) = 2.83 from their starts. A rock (R = 0.5) at (50, 0).
fesd::SceneTask slowPushingTask();

/// A pusher (R = 0.5, |u| <= 4) at (-2, 0) and a puck (R = 0.5) to be pushed from the origin to
/// (3, 0) (weight 100) in T = 2 on 20 intervals.
fesd::SceneTask pushAlongX();

/// pushAlongX with a smaller puck (R = 0.3) 0.05 above a wall (y >= -0.35) that the pusher
/// (R = 0.5, starting at (-2, 0.3)) cannot get straight behind it along: pushed, the puck slides
/// along the wall and ends 0.05 from its target (3, 0) at best.
fesd::SceneTask pushAlongAWall();

/// A pusher (R = 0.2, |u| <= 2) at (-1.5, 0.2) and a turning square box of four spheres
/// (R = 0.25 at (+-0.25, +-0.25)) at the origin, yaw 0.3, to be pushed into the corner of the
/// walls x <= 1.5 and y >= -1 and squared to them: to (1, -0.5), yaw 0 (weights 100) in
/// T = 4 on 20 intervals.
fesd::SceneTask boxIntoACorner();

/// A pusher (R = 0.03, |u| <= 0.3) floating at height `pusher_height` 0.2 behind a puck
/// (R = 0.05) that rests on a table z >= 0 at the origin, T = 2 on 10 intervals; no target.
fesd::SceneTask puckOnATable(double pusher_height = 0.05);

/// The node's default grid (3 elements, 2 stages) and verification grid (n_s = 3, N_FE = 6).
fesd::SceneSolveOptions nodeGridOptions();

/// What the node asks of a robot solve: every pair in reach modelled, the plan verified.
fesd::SceneSolveOptions robotSolveOptions();

}  // namespace fesd_test
