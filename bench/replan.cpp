// replan: the showcase's object target moved step by step, each plan warm-started from the
// last, against a cold solve of the same task: iterations, wall times and their ratio.
#include <algorithm>
#include <cstdio>
#include <vector>

#include "commands.h"
#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd_bench {
namespace {

fesd::SceneTask movedTarget(int intervals, double dx) {
  return fesd::manipulation_example::task(intervals, Eigen::Vector2d(dx, 10.0));
}

/// The fastest of `repeat` solves (wall seconds of the whole solveSceneTask) and its outcome.
fesd::SceneOutcome timed(const fesd::SceneTask& task, const fesd::SceneSolveOptions& options,
                         int repeat, double& seconds) {
  fesd::SceneOutcome outcome;
  seconds = 1e300;
  for (int r = 0; r < repeat; ++r) {
    fesd::Stopwatch stopwatch;
    outcome = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
    seconds = std::min(seconds, stopwatch.wallSeconds());
  }
  return outcome;
}

}  // namespace

int replan(const Arguments& args) {
  const int intervals = args.integer("intervals", 40);
  const int steps = args.integer("steps", 10);
  const double step = args.number("step", 0.03);
  const int repeat = args.integer("repeat", 3);
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = args.integer("elements", 3);
  options.ocp.homotopy.wall_time_budget = args.number("budget", 120.0);
  args.rejectUnused();
  double seconds = 0.0;
  fesd::SceneOutcome previous = timed(movedTarget(intervals, 0.0), options, 1, seconds);
  std::printf(
      "target_dx,warm_status,warm_started,warm_iterations,warm_s,cold_status,"
      "cold_iterations,cold_s,ratio,objective_warm,objective_cold\n");
  bool all_warm = previous.status == fesd::SolveStatus::kSuccess;
  std::vector<double> ratios;
  for (int k = 1; k <= steps; ++k) {
    const fesd::SceneTask task = movedTarget(intervals, k * step);
    fesd::SceneSolveOptions warm_options = options;
    warm_options.previous = &previous;
    double warm_seconds = 0.0, cold_seconds = 0.0;
    fesd::SceneOutcome warm = timed(task, warm_options, repeat, warm_seconds);
    const fesd::SceneOutcome cold = timed(task, options, repeat, cold_seconds);
    const bool warm_started = warm.start == fesd::OcpStart::kPrevious;
    all_warm = all_warm && warm_started && warm.status == fesd::SolveStatus::kSuccess;
    ratios.push_back(warm_seconds / cold_seconds);
    std::printf("%.3f,%s,%d,%d,%.4f,%s,%d,%.4f,%.3f,%.7g,%.7g\n", k * step,
                fesd::statusName(warm.status).c_str(), warm_started, warm.report.iterations,
                warm_seconds, fesd::statusName(cold.status).c_str(), cold.report.iterations,
                cold_seconds, ratios.back(), warm.report.objective, cold.report.objective);
    std::fflush(stdout);
    previous = std::move(warm);
  }
  std::sort(ratios.begin(), ratios.end());
  std::printf(
      "# median warm/cold wall-time ratio %.3f (best of %d each); every replan warm and "
      "successful: %s\n",
      ratios[ratios.size() / 2], repeat, all_warm ? "yes" : "no");
  return all_warm ? 0 : 1;
}

}  // namespace fesd_bench
