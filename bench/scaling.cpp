// scaling: how solve time grows with the horizon's resolution (N_ctrl, on the manipulation
// showcase) and with the number of bodies (lanes of pusher and puck), with pair pruning on/off.
#include <cstdio>
#include <stdexcept>
#include <string>

#include "commands.h"
#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/planning/scene_solver.h"

namespace fesd_bench {
namespace {

/// `lanes` lanes 40 apart, each a pusher (R = 0.5, |u| <= 2) at (-3, y) and a puck at (0, y)
/// to be pushed to (0.5, y) in T = 2 (a pushed pair moves at half the commanded speed, as the
/// projection shares it between them: after the approach the puck could make 1): every lane is
/// the same small problem, and no two lanes can touch while the reach bound (D = 2 sqrt(8
/// lanes)) stays below half their gap (8 lanes: 16).
fesd::SceneTask lanesTask(int lanes, int intervals) {
  fesd::SceneTask task;
  task.horizon = 2.0;
  task.num_intervals = intervals;
  for (int lane = 0; lane < lanes; ++lane) {
    const double y = 40.0 * lane;
    const std::string index = std::to_string(lane);
    task.scene.bodies().push_back({"pusher_" + index, 0.5, Eigen::Vector2d(-3.0, y), true});
    task.scene.bodies().push_back({"puck_" + index, 0.5, Eigen::Vector2d(0.0, y), false});
    fesd::BodyTask pusher, puck;
    pusher.max_speed = 2.0;
    puck.target = Eigen::Vector2d(0.5, y);
    puck.target_weight = 100.0;
    task.bodies.push_back(pusher);
    task.bodies.push_back(puck);
  }
  return task;
}

fesd::SceneOutcome solveTask(const fesd::SceneTask& task, bool pruning,
                             const fesd::OcpOptions& options) {
  fesd::SceneSolveOptions scene_options;
  scene_options.ocp = options;
  scene_options.prune_pairs = pruning;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, fesd::TaskLimits{}, scene_options);
  if (!outcome.solved()) {
    throw std::runtime_error("scaling: task not solved: " + outcome.invalid + outcome.infeasible);
  }
  return outcome;
}

void printRun(const char* sweep, int intervals, int bodies, bool pruning,
              const fesd::SceneOutcome& run) {
  const fesd::MpccReport& report = run.report;
  std::printf("%s,%d,%d,%s,%d,%d,%d,%s,%d,%.3f,%.3f\n", sweep, intervals, bodies,
              pruning ? "on" : "off", run.modelledPairs(), run.sizes.variables,
              run.sizes.complementarities, fesd::statusName(run.status).c_str(), report.iterations,
              report.cpu_seconds, report.wall_seconds);
  std::fflush(stdout);
}

}  // namespace

int scaling(const Arguments& args) {
  const std::vector<int> intervals = args.integers("intervals", {10, 20, 30, 40, 60, 80});
  const std::vector<int> lanes = args.integers("lanes", {1, 2, 3, 4, 6, 8});
  const int lane_intervals = args.integer("lane-intervals", 10);
  const std::vector<std::string> sweeps = args.texts("sweeps", {"intervals", "bodies"});
  fesd::OcpOptions options;
  options.discretization.num_elements = args.integer("elements", 2);
  options.discretization.num_stages = args.integer("stages", 2);
  options.homotopy.wall_time_budget = args.number("budget", 120.0);
  args.rejectUnused();

  std::printf(
      "sweep,intervals,bodies,pruning,modelled_pairs,nlp_variables,complementarities,status,"
      "ipopt_iterations,cpu_s,wall_s\n");
  for (const std::string& sweep : sweeps) {
    if (sweep == "intervals") {
      for (int n : intervals) {
        printRun("intervals", n, 3, true,
                 solveTask(fesd::manipulation_example::task(n), true, options));
      }
    } else if (sweep == "bodies") {
      for (bool pruning : {true, false}) {
        for (int k : lanes) {
          printRun("bodies", lane_intervals, 2 * k, pruning,
                   solveTask(lanesTask(k, lane_intervals), pruning, options));
        }
      }
    } else {
      throw std::invalid_argument("unknown sweep '" + sweep + "' (intervals, bodies)");
    }
  }
  return 0;
}

}  // namespace fesd_bench
