#pragma once

#include <limits>
#include <string>
#include <vector>

#include "fesd_trajopt/planning/scene_solver.h"
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
/// A pusher and a puck (a helper pusher beside it in about half the scenes) with 3-7
/// posts, one or two on the push line, a pusher's width apart and clear of the start and the
/// target, and up to 3 stones (passive discs) off the line: pushes that must go round.
PlanningScene postsScene(unsigned seed);

/// "push": a pusher and a puck of random radii (0.2 to 0.8) in the plane or (a third of them) in
/// space, the puck's target 1 to 4 away in a random direction, the pusher starting beside or
/// behind it, 0.2 to 2 away. Reachable.
PlanningScene pushScene(unsigned seed);

/// "wall": a push along a wall that touches the puck at the start (a third), nearly touches it
/// (gap below 0.05) or runs up to 0.3 beside it, the target as near the wall. Reachable.
PlanningScene wallScene(unsigned seed);

/// "beside": a push with one to three fixed obstacles beside the puck's path, 0.02 to 0.3 clear
/// of its swept corridor. Reachable.
PlanningScene besideScene(unsigned seed);

/// "second": a push with a second passive puck near the path (0.05 to 1 clear of the swept
/// corridor, or in it for a quarter of the seeds). Reachable.
PlanningScene secondBodyScene(unsigned seed);

/// "showcase": the showcase with the object's start moved within 1.5 of the origin and its
/// target within 2 of (0, 10), or (a third of the seeds) the target moved sideways to |x| in
/// [0.9, 1.5], beyond where the actuators' workspace bounds let them push it (x <= -2.5 and
/// x >= 2.5 keep them from behind the object): unreachable.
PlanningScene showcaseScene(unsigned seed);

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
