#pragma once

#include <limits>
#include <string>
#include <vector>

#include "fesd_trajopt/scene/scene_solver.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// Seeded random planning tasks of the kinds users bring, for the planning sweep (fesd_bench
/// planning-sweep) and its tests. Each is a deterministic function of its family and seed (its
/// own uniform numbers from std::mt19937's raw output).
namespace planning_scenes {

struct PlanningScene {
  std::string family;
  unsigned seed = 0;
  SceneTask task;
  int pushed = -1;          ///< the body whose target the scene is about
  bool reachable = true;    ///< whether the generator made that target reachable
  std::string description;  ///< one line: base, extra bodies and obstacles
};

/// The families this generator knows.
const std::vector<std::string>& families();

/// The scene of a family and seed; throws std::invalid_argument for an unknown family.
PlanningScene scene(const std::string& family, unsigned seed);

/// "cluttered": the showcase (two actuators push the object to (0, 10)) or a pusher and a puck
/// (the puck 2 to 3.5 from its start in any direction), with 5 to 20 extra bodies scattered
/// around: two thirds passive discs (up to two of them in the pushed body's way, the rest
/// anywhere), one third fixed obstacles, which keep clear of the pushed body's corridor, its
/// target and the stretch beyond it, so the target stays reachable by pushing through.
PlanningScene clutteredScene(unsigned seed);

/// A planning scene solved and checked as the sweep reports it.
struct PlanningRun {
  SceneOutcome outcome;
  double wall_seconds = 0.0;
  double target_distance = 0.0;  ///< of the pushed body's end from its target
  /// The smallest gap of any pair in reach at the plan's element boundaries, relative to the
  /// pair's size (pairSize); negative: penetration.
  double plan_gap = 0.0;
  Verification verification;  ///< with every pair in reach modelled
  double verification_seconds = 0.0;
  /// plan_gap along the verification's element boundaries (when it succeeded).
  double verification_gap = std::numeric_limits<double>::quiet_NaN();
};

/// Solves a scene with `options` (its verify flag aside), then, if that succeeded, verifies it
/// on `fine`.
PlanningRun runScene(const PlanningScene& scene, const SceneSolveOptions& options,
                     const SimulationOptions& fine);

/// The smallest gap of the pairs in reach (modelled or checked) over the states of a trajectory
/// of the task's full scene, each relative to its pair's size.
double smallestRelativeGap(const SceneTask& task, const std::vector<PairDecision>& decisions,
                           const std::vector<Eigen::VectorXd>& states);

}  // namespace planning_scenes
}  // namespace fesd
