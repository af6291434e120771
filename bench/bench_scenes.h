#pragma once

#include <memory>
#include <string>

#include "bench_args.h"
#include "fesd_trajopt/kinematics/kinematic_model.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd_bench {

/// The showcase plus `rocks` passive discs (R = 1, no target) at (-12 + 4 i, -12): with all seven
/// it is node_roundtrip's ten_discs_in_reach.
fesd::SceneTask showcaseWithRocks(int intervals, int rocks);

/// The options of the node's default request (config/fesd_trajopt.yaml: 3 elements, 2 stages,
/// lazy pairs with margin 0.1, verified on n_s = 3, N_FE = 6) within `budget` seconds; its
/// accuracy target is 1e-2 (solveToAccuracy).
fesd::SceneSolveOptions nodeDefaultOptions(double budget);

/// --length-scaling=true|false: solve in units of the task's length scale (the default) or in
/// its own units as given (SceneSolveOptions::length_scaling); --evaluation-threads=measured|
/// one|two: how many threads evaluate the NLP's functions (DiscretizationOptions).
void applySceneArguments(const Arguments& args, fesd::SceneSolveOptions& options);

/// The node's default request of the default scene with `options` up the ladder to `accuracy`,
/// three times (the first pays for what a node pays once: analyses, caches): prints a "#" line
/// and returns the median of the other two runs' seconds.
double timeDefaultScene(const fesd::SceneSolveOptions& options, double accuracy);

/// A robot of config/robots, built from its URDF; throws naming the file if that fails.
std::shared_ptr<const fesd::KinematicModel> shippedRobot(const std::string& file);

}  // namespace fesd_bench
