// sweep-accuracy: what accuracy costs in time over the planning sweep's scenes. Each scene climbs
// the node's accuracy ladder to the end (a target no rung meets): per rung its discretisation,
// wall time (solve and verification) and verification error, CSV.
#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "bench_args.h"
#include "commands.h"
#include "fesd_trajopt/examples/planning_scenes.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"

namespace fesd_bench {

int sweepAccuracy(const Arguments& args) {
  namespace ps = fesd::planning_scenes;
  const std::vector<std::string> families =
      args.texts("families", {"push", "wall", "beside", "second", "showcase"});
  const int first_seed = args.integer("first-seed", 0);
  const int scenes = args.integer("scenes", 3);
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = args.integer("elements", 3);
  options.ocp.discretization.num_stages = args.integer("stages", 2);
  options.ocp.homotopy.wall_time_budget = args.number("budget", 120.0);
  // The node's verification grid (config/fesd_trajopt.yaml).
  options.verification.num_stages = 3;
  options.verification.num_elements = 6;
  fesd::TaskLimits limits;
  limits.max_stages = args.integer("max-stages", 4);
  limits.max_elements = args.integer("max-elements", 4);
  args.rejectUnused();

  std::printf("family,seed,rung,n_s,n_fe,status,wall_s,cumulative_s,verification_error\n");
  for (const std::string& family : families) {
    for (int seed = first_seed; seed < first_seed + scenes; ++seed) {
      const ps::PlanningScene scene = ps::scene(family, seed);
      // No rung meets a negative target: the ladder runs to its end (or the budget's) and
      // reports every rung.
      const fesd::SceneOutcome outcome = fesd::solveToAccuracy(
          scene.task, limits, options, -std::numeric_limits<double>::infinity());
      double cumulative = 0.0;
      for (size_t r = 0; r < outcome.refinements.size(); ++r) {
        const fesd::AccuracyRung& rung = outcome.refinements[r];
        cumulative += rung.wall_seconds;
        std::printf("%s,%u,%zu,%d,%d,%s,%.3f,%.3f,%.3g\n", family.c_str(), scene.seed, r + 1,
                    rung.stages,
                    *std::max_element(rung.interval_elements.begin(), rung.interval_elements.end()),
                    fesd::statusName(rung.status).c_str(), rung.wall_seconds, cumulative,
                    rung.verification_error);
      }
      if (!outcome.solved()) {
        std::printf("%s,%u,0,0,0,refused,0,0,inf\n", family.c_str(), scene.seed);
      }
      std::fflush(stdout);
    }
  }
  return 0;
}

}  // namespace fesd_bench
