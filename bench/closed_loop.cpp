// closed-loop: plans executed with feedback against open loop over the planning sweep's scenes:
// the first plan at the node's defaults, its open-loop replay, then replans every --every
// intervals from the state the plant (a fine re-simulation) reached, warm from the rest of the
// plan before. Per scene the pushed body's distance from its target open and closed loop, and
// what the replans cost against the first plan. CSV, then a summary.
#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_scenes.h"
#include "commands.h"
#include "fesd_trajopt/examples/planning_scenes.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/planning/closed_loop.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd_bench {

int closedLoop(const Arguments& args) {
  namespace ps = fesd::planning_scenes;
  const std::vector<std::string> families = args.texts("families", {"cluttered"});
  const int first_seed = args.integer("first-seed", 0);
  const int scenes = args.integer("scenes", 12);
  const double horizon = args.number("horizon", 0.0);
  const int intervals = args.integer("intervals", 0);
  const double min_open_loop = args.number("min-open-loop", 0.0);
  const bool each_replan = args.flag("replans", false);
  fesd::ClosedLoopOptions options;
  options.replan_every = args.integer("every", 3);
  options.first = nodeDefaultOptions(args.number("budget", 60.0));
  applyHomotopyArguments(args, options.first.ocp.homotopy);
  options.replan = options.first;
  options.replan.verify = false;                // the fastest answer
  options.plant.discretization.num_stages = 3;  // the verification's grid
  options.plant.discretization.num_elements = 6;
  args.rejectUnused();
  std::printf(
      "family,seed,first_status,first_s,verification_error,open_loop_error,open_loop_target,"
      "closed_loop_target,replans,warm,replans_s,replans_over_first,description\n");
  int loops = 0, within = 0;
  std::vector<double> ratios;
  for (const std::string& family : families) {
    for (int seed = first_seed; seed < first_seed + scenes; ++seed) {
      ps::PlanningScene scene = ps::scene(family, seed);
      if (horizon > 0.0) scene.task.horizon = horizon;
      if (intervals > 0) scene.task.num_intervals = intervals;
      fesd::Stopwatch first_time;
      const fesd::SceneOutcome first = fesd::solveToAccuracy(scene.task, fesd::TaskLimits{},
                                                             options.first, options.first_accuracy);
      const double first_seconds = first_time.wallSeconds();
      const fesd::Scene& s = scene.task.scene;
      const Eigen::VectorXd& target = scene.task.bodies[scene.pushed].target;
      const fesd::Verification& v = first.verification;
      const double open_target =
          v.open_loop.states.empty()
              ? std::numeric_limits<double>::quiet_NaN()
              : (s.position(scene.pushed, v.open_loop.finalState()) - target).norm();
      if (!(open_target > min_open_loop)) continue;
      options.first_plan = &first;
      fesd::ClosedLoopRun run = fesd::executeWithFeedback(scene.task, fesd::TaskLimits{}, options);
      run.first_seconds = first_seconds;
      const double closed_target = run.status == fesd::SolveStatus::kSuccess
                                       ? (s.position(scene.pushed, run.end) - target).norm()
                                       : std::numeric_limits<double>::quiet_NaN();
      const int warm =
          static_cast<int>(std::count_if(run.replans.begin(), run.replans.end(),
                                         [](const fesd::Replan& r) { return r.warm_started; }));
      ++loops;
      within += closed_target <= 1e-2;
      ratios.push_back(run.replan_seconds / run.first_seconds);
      std::printf("%s,%u,%s,%.3f,%.3g,%.3g,%.3g,%.3g,%zu,%d,%.3f,%.2f,%s\n", family.c_str(),
                  scene.seed, fesd::statusName(run.first.status).c_str(), run.first_seconds,
                  v.error, v.open_loop_error, open_target, closed_target, run.replans.size(), warm,
                  run.replan_seconds, run.replan_seconds / run.first_seconds,
                  scene.description.c_str());
      for (const fesd::Replan& replan : run.replans) {
        if (!each_replan) break;
        std::string steps;
        for (const fesd::HomotopyStep& step : replan.history) {
          char item[32];
          std::snprintf(item, sizeof item, " %.0e:%d", step.sigma, step.iterations);
          steps += item;
        }
        std::printf(
            "#   replan after %d intervals: %s, %s, %d round(s), %d Ipopt iterations, %.3f "
            "s:%s\n",
            replan.after_intervals, fesd::statusName(replan.status).c_str(),
            replan.warm_started ? "warm" : "cold", replan.pair_rounds, replan.iterations,
            replan.seconds, steps.c_str());
        if (replan.status != fesd::SolveStatus::kSuccess) {
          std::printf("#     %s\n", replan.message.c_str());
        }
      }
      if (run.status != fesd::SolveStatus::kSuccess) {
        std::fprintf(stderr, "# %s %u: %s\n", family.c_str(), scene.seed, run.message.c_str());
      }
      std::fflush(stdout);
    }
  }
  std::sort(ratios.begin(), ratios.end());
  std::printf(
      "# %d loops: %d end within 1e-2 of the target closed loop; replans over the first "
      "plan's time: median %.2f, largest %.2f\n",
      loops, within, ratios.empty() ? 0.0 : ratios[ratios.size() / 2],
      ratios.empty() ? 0.0 : ratios.back());
  return 0;
}

}  // namespace fesd_bench
