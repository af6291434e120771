// planning-sweep: seeded random planning scenes (examples/planning_scenes.h) solved as the node
// solves them, each verified with every pair in reach modelled: status, wall time, pairs in
// reach / modelled / rounds, the pushed body's distance from its target, penetration of the
// plan and of the verification. CSV, then a summary against the showcase's wall time.
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
#include "fesd_trajopt/solver/stopwatch.h"
#include "showcase_reference.h"

namespace fesd_bench {
namespace {

/// Ipopt iterations of each homotopy step, "a/b/c".
std::string stepIterations(const fesd::MpccReport& report) {
  std::string text;
  for (const fesd::HomotopyStep& step : report.history) {
    text += (text.empty() ? "" : "/") + std::to_string(step.iterations);
  }
  return text;
}

/// Each homotopy step as sigma:iterations (0: a polishing solve), "1e-2:21 0:12".
std::string stepHistory(const fesd::MpccReport& report) {
  std::string text;
  for (const fesd::HomotopyStep& step : report.history) {
    char item[48];
    std::snprintf(item, sizeof item, "%s%.0e:%d", text.empty() ? "" : " ", step.sigma,
                  step.iterations);
    text += item;
  }
  return text;
}

/// The node's default request for each scene (verified, the accuracy ladder, the node's budget
/// and pairs): status, seconds, iterations, rungs, errors; CSV, then a summary against the
/// node's default request of the default scene in the same run.
int nodeDefaultSweep(const Arguments& args, const std::vector<std::string>& families,
                     int first_seed, int scenes) {
  namespace ps = fesd::planning_scenes;
  fesd::SceneSolveOptions options = nodeDefaultOptions(args.number("budget", 120.0));
  options.first_round_margin = args.number("first-margin", options.first_round_margin);
  options.ocp.guess_sigma = args.number("guess-sigma", options.ocp.guess_sigma);
  applyHomotopyArguments(args, options.ocp.homotopy);
  applySceneArguments(args, options);
  const double accuracy = args.number("accuracy", 1e-2);
  const double horizon = args.number("horizon", 0.0);
  const int intervals = args.integer("intervals", 0);
  args.rejectUnused();
  const double default_seconds = timeDefaultScene(options, accuracy);
  std::printf(
      "family,seed,status,wall_s,ratio,ipopt_iterations,objective,rungs,pair_rounds,graze_rounds,"
      "verification_error,open_loop_error,open_loop_gain,grazes,verification_s,target_distance,"
      "certified,branch_nlps,lpecs,lpec_s,rung_changes,history,description\n");
  std::vector<double> walls;
  int count = 0, successes = 0;
  for (const std::string& family : families) {
    for (int seed = first_seed; seed < first_seed + scenes; ++seed) {
      ps::PlanningScene scene = ps::scene(family, seed);
      if (horizon > 0.0) scene.task.horizon = horizon;
      if (intervals > 0) scene.task.num_intervals = intervals;
      fesd::Stopwatch stopwatch;
      const fesd::SceneOutcome outcome =
          fesd::solveToAccuracy(scene.task, fesd::TaskLimits{}, options, accuracy);
      const double seconds = stopwatch.wallSeconds();
      ++count;
      successes += outcome.solved() && outcome.status == fesd::SolveStatus::kSuccess;
      walls.push_back(seconds);
      const double target = outcome.target_distances.empty()
                                ? std::numeric_limits<double>::quiet_NaN()
                                : outcome.target_distances[scene.pushed];
      std::string changes;
      for (size_t r = 1; r < outcome.refinements.size(); ++r) {
        const fesd::AccuracyRung& rung = outcome.refinements[r];
        char line[64];
        std::snprintf(line, sizeof line, " (%.3g s, %.2g)", rung.wall_seconds,
                      rung.verification_error);
        changes += (changes.empty() ? "" : " | ") + rung.change + line;
      }
      const fesd::Verification& v = outcome.verification;
      std::printf(
          "%s,%u,%s,%.3f,%.1f,%d,%.10g,%zu,%d,%d,%.3g,%.3g,%.3g,%zu,%.3f,%.3g,%d,%d,%d,%.3f,\"%s\","
          "%"
          "s,%s\n",
          family.c_str(), scene.seed,
          outcome.solved() ? fesd::statusName(outcome.status).c_str() : "refused", seconds,
          seconds / default_seconds, outcome.report.iterations, outcome.report.objective,
          outcome.refinements.size(), outcome.pair_rounds, outcome.graze_rounds, v.error,
          v.open_loop_error, v.open_loop_gain, v.grazes.size(), v.seconds, target,
          outcome.report.certified, outcome.report.branch_nlps, outcome.report.lpecs,
          outcome.report.lpec_seconds, changes.c_str(), stepHistory(outcome.report).c_str(),
          scene.description.c_str());
      if (!outcome.solved() || outcome.status != fesd::SolveStatus::kSuccess) {
        std::fprintf(stderr, "# %s %u: %s\n", family.c_str(), scene.seed, outcome.message.c_str());
      }
      std::fflush(stdout);
    }
  }
  const double slowest = walls.empty() ? 0.0 : *std::max_element(walls.begin(), walls.end());
  std::printf(
      "# %d scenes: %d SUCCESS; wall time median %.3f s, slowest %.3f s (%.1fx and %.1fx "
      "the default scene's)\n",
      count, successes, median(walls), slowest, median(walls) / default_seconds,
      slowest / default_seconds);
  return 0;
}

}  // namespace

int planningSweep(const Arguments& args) {
  namespace ps = fesd::planning_scenes;
  const std::vector<std::string> families = args.texts("families", ps::families());
  const int first_seed = args.integer("first-seed", 0);
  const int scenes = args.integer("scenes", 20);
  if (args.text("mode", "solve") == "node") {
    return nodeDefaultSweep(args, families, first_seed, scenes);
  }
  const std::string pairs = args.text("pairs", "lazy");
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = args.integer("elements", 3);
  options.ocp.discretization.num_stages = args.integer("stages", 2);
  options.ocp.homotopy.wall_time_budget = args.number("budget", 120.0);
  options.lazy_pairs = pairs == "lazy";
  options.pair_margin = args.number("margin", 0.1);
  options.ocp.guess_sigma = args.number("guess-sigma", options.ocp.guess_sigma);
  applyHomotopyArguments(args, options.ocp.homotopy);
  fesd::SimulationOptions fine;
  fine.discretization.num_stages = std::max(3, options.ocp.discretization.num_stages);
  fine.discretization.num_elements = 2 * options.ocp.discretization.num_elements;
  fine.wall_time_budget = options.ocp.homotopy.wall_time_budget;
  const bool with_showcase = args.flag("showcase", true);
  args.rejectUnused();
  if (pairs != "lazy" && pairs != "all") throw std::invalid_argument("--pairs=lazy|all");

  const double showcase_seconds = with_showcase ? timeShowcase(options, "# ") : 0.0;
  std::printf(
      "family,seed,bodies,obstacles,reachable,pairs,status,wall_s,ipopt_iterations,objective,"
      "homotopy_steps,step_iterations,pairs_in_reach,modelled,checked,rounds,target_distance,plan_"
      "gap,guess_residual,verification_status,verification_error,verification_gap,verification_s,"
      "description\n");
  std::vector<double> walls;
  int count = 0, failed = 0, missed = 0, penetrating = 0;
  for (const std::string& family : families) {
    for (int seed = first_seed; seed < first_seed + scenes; ++seed) {
      const ps::PlanningScene scene = ps::scene(family, seed);
      const ps::PlanningRun run = ps::runScene(scene, options, fine);
      const fesd::SceneOutcome& outcome = run.outcome;
      const bool ok = outcome.solved() && outcome.status == fesd::SolveStatus::kSuccess;
      ++count;
      failed += !ok;
      missed += ok && run.target_distance > 1e-3;
      penetrating += run.plan_gap < -1e-6 || run.verification_gap < -1e-6;
      walls.push_back(run.wall_seconds);
      std::printf(
          "%s,%u,%zu,%zu,%d,%s,%s,%.3f,%d,%.10g,%zu,%s,%d,%d,%d,%d,%.3g,%.3g,%.3g,%s,%.3g,%.3g,%."
          "3f,%s\n",
          family.c_str(), scene.seed, scene.task.scene.bodies().size(),
          scene.task.scene.obstacles().size(), scene.reachable, pairs.c_str(),
          outcome.solved() ? fesd::statusName(outcome.status).c_str() : "refused", run.wall_seconds,
          outcome.report.iterations, outcome.report.objective, outcome.report.history.size(),
          stepIterations(outcome.report).c_str(), outcome.modelledPairs() + outcome.checkedPairs(),
          outcome.modelledPairs(), outcome.checkedPairs(), outcome.pair_rounds, run.target_distance,
          run.plan_gap, outcome.guess_residual, fesd::statusName(run.verification.status).c_str(),
          run.verification.error, run.verification_gap, run.verification_seconds,
          scene.description.c_str());
      if (!ok)
        std::fprintf(stderr, "# %s %u: %s\n", family.c_str(), scene.seed, outcome.message.c_str());
      std::fflush(stdout);
    }
  }
  const double slowest = walls.empty() ? 0.0 : *std::max_element(walls.begin(), walls.end());
  std::printf(
      "# %d scenes: %d not SUCCESS, %d SUCCESS with the target missed by > 1e-3, %d with "
      "penetration below -1e-6 of a pair's size; wall time median %.3f s, slowest %.3f s",
      count, failed, missed, penetrating, median(walls), slowest);
  if (showcase_seconds > 0.0) {
    std::printf(" (%.2fx and %.2fx the showcase's)", median(walls) / showcase_seconds,
                slowest / showcase_seconds);
  }
  std::printf("\n");
  return 0;
}

}  // namespace fesd_bench
