#include "fesd_trajopt/examples/planning_scenes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/scene/pair_check.h"
#include "fesd_trajopt/scene/seeded_random.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {
namespace planning_scenes {
namespace {

/// Distance from p to the segment from a to b.
double segmentDistance(const Eigen::VectorXd& p, const Eigen::VectorXd& a,
                       const Eigen::VectorXd& b) {
  const Eigen::VectorXd d = b - a;
  const double s = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (a + s * d - p).norm();
}

/// Whether a disc at p (radius r) keeps `gap` clear of every body and obstacle.
bool fits(const DiscScene& scene, const Eigen::VectorXd& p, double r, double gap) {
  for (const SceneBody& b : scene.bodies()) {
    if ((b.position - p).norm() < b.radius + r + gap) return false;
  }
  for (const SceneObstacle& o : scene.obstacles()) {
    if ((o.position - p).norm() < o.radius + r + gap) return false;
  }
  return true;
}

/// A pusher (R = 0.5, |u| <= 4) and a puck (R = 0.5) at the origin, the puck's target 2 to 3.5
/// away in a random direction, the pusher 2 behind it, T = 3, N = 20.
SceneTask pusherAndPuck(SeededUniform& random) {
  const Eigen::VectorXd direction = random.unitVector(2);
  SceneTask task;
  task.scene.bodies() = {{"pusher", 0.5, Eigen::VectorXd(-2.0 * direction), true},
                         {"puck", 0.5, Eigen::Vector2d::Zero(), false}};
  task.bodies.resize(2);
  task.bodies[0].max_speed = 4.0;
  task.bodies[1].target = random(2.0, 3.5) * direction;
  task.bodies[1].target_weight = 100.0;
  task.horizon = 3.0;
  task.num_intervals = 20;
  return task;
}

}  // namespace

const std::vector<std::string>& families() {
  static const std::vector<std::string> names{"cluttered"};
  return names;
}

PlanningScene scene(const std::string& family, unsigned seed) {
  if (family == "cluttered") return clutteredScene(seed);
  throw std::invalid_argument("planning_scenes: unknown family '" + family + "'");
}

PlanningScene clutteredScene(unsigned seed) {
  SeededUniform random(seed);
  PlanningScene result;
  result.family = "cluttered";
  result.seed = seed;
  const bool showcase = random() < 0.5;
  SceneTask task = showcase ? manipulation_example::task(40) : pusherAndPuck(random);
  const int pushed = showcase ? 2 : 1;
  const double scale = showcase ? 1.0 : 0.4;  // extra bodies' radii and gaps
  DiscScene& scene = task.scene;
  const Eigen::VectorXd start = scene.bodies()[pushed].position;
  const Eigen::VectorXd target = task.bodies[pushed].target;
  const Eigen::VectorXd direction = (target - start).normalized();
  const double radius = scene.bodies()[pushed].radius;
  // Obstacles keep clear of the corridor (and the stretch beyond the target where shoved discs
  // end up) by two of the largest extra discs.
  const Eigen::VectorXd beyond = target + 4.0 * radius * direction;
  const double corridor = radius + 2.0 * 2.0 * 1.5 * scale;
  Eigen::VectorXd low = start.cwiseMin(target).array() - 6.0 * radius - 4.0 * scale;
  Eigen::VectorXd high = start.cwiseMax(target).array() + 6.0 * radius + 4.0 * scale;
  if (showcase) {
    low = Eigen::Vector2d(-14.0, -8.0);
    high = Eigen::Vector2d(14.0, 16.0);
  }
  const int extras = random.integer(5, 20);
  const int obstacles = extras / 3, in_the_way = std::min(random.integer(0, 2), extras - obstacles);
  int discs = 0, tries = 0;
  while (discs + static_cast<int>(scene.obstacles().size()) < extras && ++tries < 10000) {
    const bool obstacle =
        static_cast<int>(scene.obstacles().size()) < obstacles && discs >= extras - obstacles;
    const double r = random(0.5, 1.5) * scale;
    Eigen::VectorXd p(2);
    if (!obstacle && discs < in_the_way) {
      const Eigen::Vector2d side(-direction(1), direction(0));
      p = start + random(0.35, 0.75) * (target - start) + random(-1.0, 1.0) * (radius + r) * side;
    } else {
      p = Eigen::Vector2d(random(low(0), high(0)), random(low(1), high(1)));
    }
    if (!fits(scene, p, r, 0.1 * scale)) continue;
    if (obstacle && (segmentDistance(p, start, beyond) < corridor + r ||
                     (p - target).norm() < 2.0 * (radius + r))) {
      continue;
    }
    if (obstacle) {
      scene.obstacles().push_back({"post_" + std::to_string(scene.obstacles().size()), r, p});
    } else {
      scene.bodies().push_back({"disc_" + std::to_string(discs++), r, p, false});
      task.bodies.emplace_back();
    }
  }
  std::ostringstream text;
  text << "cluttered seed " << seed << ": " << (showcase ? "showcase" : "pusher and puck")
       << " with " << discs << " passive discs (" << in_the_way << " in the way) and "
       << scene.obstacles().size() << " obstacles";
  result.task = task;
  result.pushed = pushed;
  result.description = text.str();
  return result;
}

double smallestRelativeGap(const SceneTask& task, const std::vector<PairDecision>& decisions,
                           const std::vector<Eigen::VectorXd>& states) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const PairDecision& decision : decisions) {
    if (!decision.modelled && !decision.checked) continue;
    const double size = pairSize(task.scene, decision.pair);
    for (const Eigen::VectorXd& x : states) {
      smallest = std::min(smallest, pairGap(task.scene, decision.pair, x) / size);
    }
  }
  return smallest;
}

PlanningRun runScene(const PlanningScene& scene, const SceneSolveOptions& options,
                     const SimulationOptions& fine) {
  PlanningRun run;
  SceneSolveOptions solve = options;
  solve.verify = false;
  Stopwatch solve_time;
  run.outcome = solveSceneTask(scene.task, TaskLimits{}, solve);
  run.wall_seconds = solve_time.wallSeconds();
  if (!run.outcome.solved()) return run;
  const DiscScene& s = scene.task.scene;
  run.target_distance = (s.position(scene.pushed, run.outcome.trajectory.finalState()) -
                         scene.task.bodies[scene.pushed].target)
                            .norm();
  run.plan_gap =
      smallestRelativeGap(scene.task, run.outcome.decisions, run.outcome.trajectory.states);
  if (run.outcome.status != SolveStatus::kSuccess) return run;
  Stopwatch verification_time;
  run.verification = verifyOutcome(scene.task, run.outcome, fine, options.pair_margin);
  run.verification_seconds = verification_time.wallSeconds();
  if (run.verification.status == SolveStatus::kSuccess) {
    run.verification_gap =
        smallestRelativeGap(scene.task, run.outcome.decisions, run.verification.trajectory.states);
  }
  return run;
}

}  // namespace planning_scenes
}  // namespace fesd
