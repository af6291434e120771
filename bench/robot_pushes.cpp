// robot-pushes: every shipped robot push (examples/robot_scenes.h; the Panda's also with a 4 cm
// puck) through the node's default request (verified, the accuracy ladder, the node's pairs: all
// up to 32 in reach, else lazy; --node-horizon: the node's 5 s and 40 intervals, as a request
// that gives neither):
// status, seconds and their ratio to the default scene's in the same run, Ipopt iterations of
// the answer's rung, the pushed body's distance from its target (and yaw), whether it stayed on
// its support at every element boundary, and the smallest gap of every pair in reach; CSV.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <limits>
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "bench_args.h"
#include "bench_scenes.h"
#include "commands.h"
#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd_bench {
namespace {

struct RobotScene {
  std::string name;
  std::function<fesd::SceneTask()> task;
};

std::vector<RobotScene> robotScenes() {
  return {
      {"panda_puck", [] { return fesd::pandaPushTask(shippedRobot("panda_spherized.urdf")); }},
      {"panda_puck_4cm",
       [] { return fesd::pandaSmallPuckTask(shippedRobot("panda_spherized.urdf")); }},
      {"panda_bar", [] { return fesd::pandaBarTask(shippedRobot("panda_spherized.urdf")); }},
      {"ur3e_puck", [] { return fesd::ur3ePushTask(shippedRobot("ur3e_spherized.urdf")); }},
      {"planar_iiwa_disc",
       [] { return fesd::planarIiwaPushTask(shippedRobot("planar_iiwa.urdf")); }},
      {"planar_arm_disc", [] { return fesd::planarArmPushTask(shippedRobot("planar_arm.urdf")); }},
  };
}

/// The largest change of the pushed body's height over the element boundaries (0: it stayed on
/// its support); NaN in a planar scene.
double heightChange(const fesd::SceneTask& task, const fesd::Trajectory& trajectory) {
  const fesd::Scene& scene = task.scene;
  if (scene.dimension() != 3 || trajectory.states.empty()) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  const double start = scene.bodies()[0].position(2);
  double change = 0.0;
  for (const Eigen::VectorXd& x : trajectory.states) {
    change = std::max(change, std::fabs(scene.position(0, x)(2) - start));
  }
  return change;
}

}  // namespace

int robotPushes(const Arguments& args) {
  fesd::SceneSolveOptions options = nodeDefaultOptions(args.number("budget", 120.0));
  options.all_pairs_up_to = args.integer("all-pairs-up-to", 32);
  applyHomotopyArguments(args, options.ocp.homotopy);
  applySceneArguments(args, options);
  const double accuracy = args.number("accuracy", 1e-2);
  const std::vector<std::string> only = args.texts("scenes", {});
  // What a request that names neither gets: the node's horizon and intervals.
  const bool node_grid = args.flag("node-horizon", false);
  const int repeat = std::max(1, args.integer("repeat", 3));
  args.rejectUnused();
  const double default_seconds = timeDefaultScene(options, accuracy);
  std::printf(
      "scene,status,wall_s,ratio,ipopt_iterations,rungs,target_distance,yaw_error_deg,"
      "height_change,smallest_gap,verification_error,length_scale\n");
  for (const RobotScene& robot : robotScenes()) {
    if (!only.empty() && std::find(only.begin(), only.end(), robot.name) == only.end()) continue;
    fesd::SceneTask task = robot.task();
    if (node_grid) {
      task.horizon = 5.0;
      task.num_intervals = 40;
    }
    // Timed as the default scene is: the median of the runs after the first (which also pays
    // the process's first touch of the memory a robot's solve needs).
    fesd::SceneOutcome outcome;
    std::vector<double> runs;
    for (int run = 0; run < repeat; ++run) {
      fesd::Stopwatch stopwatch;
      outcome = fesd::solveToAccuracy(task, fesd::TaskLimits{}, options, accuracy);
      runs.push_back(stopwatch.wallSeconds());
    }
    const double seconds =
        runs.size() > 1 ? median(std::vector<double>(runs.begin() + 1, runs.end())) : runs[0];
    std::vector<fesd::ContactPair> in_reach;
    for (const fesd::PairDecision& decision : outcome.decisions) {
      if (decision.modelled || decision.checked) in_reach.push_back(decision.pair);
    }
    const double yaw = outcome.target_yaw_distances.empty() ? NAN : outcome.target_yaw_distances[0];
    std::printf("%s,%s,%.3f,%.1f,%d,%zu,%.3g,%.3g,%.3g,%.3g,%.3g,%.4g\n", robot.name.c_str(),
                outcome.solved() ? fesd::statusName(outcome.status).c_str() : "refused", seconds,
                seconds / default_seconds, outcome.report.iterations, outcome.refinements.size(),
                outcome.target_distances.empty() ? NAN : outcome.target_distances[0],
                yaw * 180.0 / M_PI, heightChange(task, outcome.trajectory),
                fesd::smallestBoundaryGap(task.scene, in_reach, outcome.trajectory),
                outcome.verification.error, outcome.length_scale);
    for (const fesd::AccuracyRung& rung : outcome.refinements) {
      std::printf("#   rung: %s (%s) %.3f s, verification error %.3g, %s\n", rung.change.c_str(),
                  rung.reason.c_str(), rung.wall_seconds, rung.verification_error,
                  fesd::statusName(rung.status).c_str());
    }

    if (outcome.status != fesd::SolveStatus::kSuccess) {
      std::fprintf(stderr, "# %s: %s\n", robot.name.c_str(),
                   outcome.solved() ? outcome.message.c_str() : outcome.invalid.c_str());
    }
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace fesd_bench
