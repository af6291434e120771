#include "fesd_trajopt/examples/planning_scenes.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/examples/seeded_random.h"
#include "fesd_trajopt/scene/pair_check.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {
namespace planning_scenes {
namespace {

/// Whether a disc at p (radius r) keeps `gap` clear of every body and obstacle.
bool fits(const Scene& scene, const Eigen::VectorXd& p, double r, double gap) {
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

/// A pusher and a puck: radii in [0.2, 0.8], the puck at the origin, its target `distance` away
/// along `direction` (weight 100), the pusher `gap` from it at an angle of up to `spread` from
/// straight behind, |u| <= 4 per coordinate, T = 3, N = 20.
SceneTask randomPush(SeededUniform& random, const Eigen::VectorXd& direction, double distance,
                     double spread) {
  const int dim = static_cast<int>(direction.size());
  const double r_pusher = random(0.2, 0.8), r_puck = random(0.2, 0.8);
  Eigen::VectorXd behind = -direction;
  Eigen::VectorXd side = random.unitVector(dim);
  side -= side.dot(direction) * direction;
  if (side.norm() > 1e-6) {
    const double angle = random(-spread, spread);
    behind = std::cos(angle) * behind + std::sin(angle) * side.normalized();
  }
  const double gap = random(0.2, 2.0);
  SceneTask task;
  task.scene = Scene(dim);
  task.scene.bodies() = {
      {"pusher", r_pusher, Eigen::VectorXd((r_pusher + r_puck + gap) * behind), true},
      {"puck", r_puck, Eigen::VectorXd::Zero(dim), false}};
  task.bodies.resize(2);
  task.bodies[0].max_speed = 4.0;
  task.bodies[1].target = distance * direction;
  task.bodies[1].target_weight = 100.0;
  task.horizon = 3.0;
  task.num_intervals = 20;
  return task;
}

PlanningScene described(const std::string& family, unsigned seed, SceneTask task, int pushed,
                        bool reachable, const std::string& what) {
  PlanningScene result;
  result.family = family;
  result.seed = seed;
  result.task = std::move(task);
  result.pushed = pushed;
  result.reachable = reachable;
  std::ostringstream text;
  text << family << " seed " << seed << ": " << what;
  result.description = text.str();
  return result;
}

/// Whether an obstacle at p of radius r would keep a body from its target (every body's, the
/// actuators' home targets too): then the target would not be reachable by construction.
bool onATarget(const SceneTask& task, const Eigen::VectorXd& p, double r) {
  for (size_t b = 0; b < task.bodies.size(); ++b) {
    const Eigen::VectorXd& target = task.bodies[b].target;
    if (target.size() && (p - target).norm() < task.scene.bodies()[b].radius + r + 0.5) return true;
  }
  return false;
}

}  // namespace

const std::vector<std::string>& families() {
  static const std::vector<std::string> names{"push",     "wall",      "beside", "second",
                                              "showcase", "cluttered", "posts"};
  return names;
}

PlanningScene scene(const std::string& family, unsigned seed) {
  if (family == "push") return pushScene(seed);
  if (family == "wall") return wallScene(seed);
  if (family == "beside") return besideScene(seed);
  if (family == "second") return secondBodyScene(seed);
  if (family == "showcase") return showcaseScene(seed);
  if (family == "cluttered") return clutteredScene(seed);
  if (family == "posts") return postsScene(seed);
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
  Scene& scene = task.scene;
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
                     (p - target).norm() < 2.0 * (radius + r) || onATarget(task, p, r))) {
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

PlanningScene postsScene(unsigned seed) {
  SeededUniform random(seed);
  SceneTask task = pusherAndPuck(random);
  const Eigen::VectorXd direction = task.bodies[1].target.normalized();
  const Eigen::Vector2d side(-direction(1), direction(0));
  const bool two_pushers = random() < 0.5;
  if (two_pushers) {
    task.scene.bodies().push_back({"helper", 0.5, Eigen::VectorXd(random(2.0, 3.0) * side), true});
    task.bodies.emplace_back();
    task.bodies.back().max_speed = 4.0;
  }
  // A longer push than pusherAndPuck's, so that there is room to go round what is on its line.
  task.bodies[1].target *= 1.5;
  const Eigen::VectorXd target = task.bodies[1].target;
  // Posts leave a pusher's width (and some) between each other and from the target, so that
  // the pushers can take the puck round them.
  const double room = 2.0 * 0.5 + 0.3, r_puck = 0.5;
  const int posts = random.integer(3, 7), on_the_line = random.integer(1, 2);
  const Eigen::VectorXd low = target.cwiseMin(Eigen::Vector2d::Zero()).array() - 3.0;
  const Eigen::VectorXd high = target.cwiseMax(Eigen::Vector2d::Zero()).array() + 3.0;
  for (int tries = 0; static_cast<int>(task.scene.obstacles().size()) < posts && tries < 1000;
       ++tries) {
    const double r = random(0.2, 0.5);
    const bool on = static_cast<int>(task.scene.obstacles().size()) < on_the_line;
    const Eigen::VectorXd p =
        on ? Eigen::VectorXd(random(0.3, 0.7) * target + random(-0.5, 0.5) * r_puck * side)
           : Eigen::VectorXd(Eigen::Vector2d(random(low(0), high(0)), random(low(1), high(1))));
    const bool apart = std::all_of(
        task.scene.obstacles().begin(), task.scene.obstacles().end(),
        [&](const SceneObstacle& o) { return (o.position - p).norm() >= o.radius + r + room; });
    if (!apart || !fits(task.scene, p, r, 0.3) || (p - target).norm() < r_puck + r + room) continue;
    task.scene.obstacles().push_back(
        {"post_" + std::to_string(task.scene.obstacles().size()), r, p});
  }
  const int stones = random.integer(0, 3);
  int placed = 0;
  for (int tries = 0; placed < stones && tries < 1000; ++tries) {
    const double r = random(0.2, 0.4);
    const Eigen::VectorXd p(Eigen::Vector2d(random(low(0), high(0)), random(low(1), high(1))));
    if (!fits(task.scene, p, r, 0.3) ||
        segmentDistance(p, Eigen::Vector2d::Zero(), target) < r_puck + r + 0.3) {
      continue;
    }
    task.scene.bodies().push_back({"stone_" + std::to_string(placed++), r, p, false});
    task.bodies.emplace_back();
  }
  std::ostringstream what;
  what << (two_pushers ? "two pushers" : "one pusher") << ", " << task.scene.obstacles().size()
       << " posts (" << std::min(on_the_line, static_cast<int>(task.scene.obstacles().size()))
       << " on the line), " << placed << " stones";
  return described("posts", seed, std::move(task), 1, true, what.str());
}

double smallestRelativeGap(const SceneTask& task, const std::vector<PairDecision>& decisions,
                           const std::vector<Eigen::VectorXd>& states) {
  double smallest = std::numeric_limits<double>::infinity();
  for (const PairDecision& decision : decisions) {
    if (!decision.modelled && !decision.checked) continue;
    const double size = task.scene.pairSize(decision.pair);
    for (const Eigen::VectorXd& x : states) {
      smallest = std::min(smallest, task.scene.pairGap(decision.pair, x) / size);
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
  const Scene& s = scene.task.scene;
  run.target_distance = (s.position(scene.pushed, run.outcome.trajectory.finalState()) -
                         scene.task.bodies[scene.pushed].target)
                            .norm();
  run.plan_gap =
      smallestRelativeGap(scene.task, run.outcome.decisions, run.outcome.trajectory.states);
  if (run.outcome.status != SolveStatus::kSuccess) return run;
  Stopwatch verification_time;
  run.verification = verifyPlan(scene.task, run.outcome.trajectory, run.outcome.decisions, fine,
                                options.pair_margin, options.graze_depth);
  run.verification_seconds = verification_time.wallSeconds();
  if (run.verification.status == SolveStatus::kSuccess) {
    run.verification_gap = run.verification.relative_gap;
  }
  return run;
}

PlanningScene pushScene(unsigned seed) {
  SeededUniform random(seed);
  const int dim = random() < 1.0 / 3.0 ? 3 : 2;
  const double distance = random(1.0, 4.0);
  const Eigen::VectorXd direction = random.unitVector(dim);
  SceneTask task = randomPush(random, direction, distance, 60.0 * M_PI / 180.0);
  std::ostringstream what;
  what << dim << "-D push of " << distance;
  return described("push", seed, std::move(task), 1, true, what.str());
}

PlanningScene wallScene(unsigned seed) {
  SeededUniform random(seed);
  const Eigen::VectorXd direction = random.unitVector(2);
  SceneTask task = randomPush(random, direction, random(1.0, 4.0), 0.0);
  const double r_puck = task.scene.bodies()[1].radius;
  // The pusher no larger than the puck: straight behind it, it fits beside the wall too.
  task.scene.bodies()[0].radius = std::min(task.scene.bodies()[0].radius, r_puck);
  const double kind = random();
  const double gap = kind < 1.0 / 3.0   ? 0.0
                     : kind < 2.0 / 3.0 ? random(0.0, 0.05)
                                        : random(0.05, 0.3);
  // The wall on one side of the push line, its normal pointing back at the puck.
  Eigen::Vector2d normal(-direction(1), direction(0));
  if (random() < 0.5) normal = -normal;
  task.scene.walls().push_back({"wall", normal, -(r_puck + gap)});
  std::ostringstream what;
  what << "push along a wall " << gap << " from the puck";
  return described("wall", seed, std::move(task), 1, true, what.str());
}

PlanningScene besideScene(unsigned seed) {
  SeededUniform random(seed);
  const Eigen::VectorXd direction = random.unitVector(2);
  const double distance = random(1.0, 4.0);
  SceneTask task = randomPush(random, direction, distance, 30.0 * M_PI / 180.0);
  const double r_puck = task.scene.bodies()[1].radius;
  const Eigen::Vector2d side(-direction(1), direction(0));
  const int count = random.integer(1, 3);
  int placed = 0;
  for (int tries = 0; placed < count && tries < 100; ++tries) {
    const double r = random(0.1, 0.6), clear = random(0.02, 0.3);
    const Eigen::VectorXd p = random(0.2, 0.9) * distance * direction +
                              (random() < 0.5 ? 1.0 : -1.0) * (r_puck + r + clear) * side;
    if (!fits(task.scene, p, r, 0.05)) continue;
    task.scene.obstacles().push_back({"post_" + std::to_string(placed++), r, p});
  }
  std::ostringstream what;
  what << "push past " << placed << " obstacle(s) beside the path";
  return described("beside", seed, std::move(task), 1, true, what.str());
}

PlanningScene secondBodyScene(unsigned seed) {
  SeededUniform random(seed);
  const Eigen::VectorXd direction = random.unitVector(2);
  const double distance = random(1.0, 4.0);
  SceneTask task = randomPush(random, direction, distance, 30.0 * M_PI / 180.0);
  const double r_puck = task.scene.bodies()[1].radius, r = random(0.2, 0.8);
  const Eigen::Vector2d side(-direction(1), direction(0));
  const bool in_the_way = random() < 0.25;
  const double lateral = in_the_way ? random(0.0, r_puck + r) : r_puck + r + random(0.05, 1.0);
  Eigen::VectorXd p =
      random(0.3, 0.8) * distance * direction + (random() < 0.5 ? 1.0 : -1.0) * lateral * side;
  if (!fits(task.scene, p, r, 0.05)) p += (3.0 * r + 1.0) * side;  // off the pusher's start
  task.scene.bodies().push_back({"second", r, p, false});
  task.bodies.emplace_back();
  return described("second", seed, std::move(task), 1, true,
                   in_the_way ? "a second puck in the way" : "a second puck beside the path");
}

PlanningScene showcaseScene(unsigned seed) {
  SeededUniform random(seed);
  SceneTask task = manipulation_example::task(40);
  const bool beyond = random() < 1.0 / 3.0;
  Eigen::Vector2d start(random(-1.5, 1.5), random(-1.5, 1.5));
  Eigen::Vector2d target(random(-2.0, 2.0), random(8.0, 12.0));
  if (beyond) {
    start.x() = 0.0;
    target.x() = (random() < 0.5 ? -1.0 : 1.0) * random(0.9, 1.5);
  } else {
    start.x() = random(-0.3, 0.3);  // the actuators reach behind it from both sides
    target.x() = random(-0.4, 0.4);
  }
  task.scene.bodies()[2].position = start;
  task.bodies[2].target = target;
  std::ostringstream what;
  what << "showcase, object (" << start.x() << ", " << start.y() << ") to (" << target.x() << ", "
       << target.y() << ")" << (beyond ? ", beyond the actuators' reach" : "");
  return described("showcase", seed, std::move(task), 2, !beyond, what.str());
}

}  // namespace planning_scenes
}  // namespace fesd
