// simulation-sweep: seeded random push scenes (push_scenes::randomPushScene) simulated on every
// sweep grid with n_s = 1..4: the status of every run, the terminal error against the closed
// form (pusher and one body, no wall) or a fine FESD run, and the outlier grids (an error more
// than 100 times both neighbours'). CSV, then a summary.
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.h"
#include "fesd_trajopt/examples/push_scenes.h"

namespace fesd_bench {

int simulationSweep(const Arguments& args) {
  namespace ps = fesd::push_scenes;
  const int first_seed = args.integer("first-seed", 0);
  const int scenes = args.integer("scenes", 24);
  const std::vector<int> stages = args.integers("stages", {1, 2, 3, 4});
  const std::vector<int> grids = args.integers("steps", ps::sweepGrids());
  const int elements = args.integer("elements", 2);
  const fesd::SimulationOptions refinement = steppingArguments(args, true);
  // 161 = 7 * 23 shares no step boundary with any sweep grid: a reference that steps exactly
  // where a grid does could share that grid's error (measured: a release 3.5e-5 before a
  // common boundary, 5.9e-8 in both).
  const int reference_steps = args.integer("reference-steps", 161);
  const double budget = args.number("budget", 60.0);
  args.rejectUnused();

  std::printf(
      "seed,dimension,bodies,wall,reference,stages,steps,contact_offset,status,failed_step,"
      "relative_error,ipopt_iterations,retried_steps,split_steps,fixed_step_parts,refined_parts,"
      "wall_s,predicted_parts,located_parts,homotopy_parts\n");
  int runs = 0, failures = 0, outlier_count = 0, reference_failures = 0;
  std::vector<std::string> findings;
  for (int seed = first_seed; seed < first_seed + scenes; ++seed) {
    const ps::PushScene scene = ps::randomPushScene(seed);
    const Eigen::VectorXd reference = ps::referenceEnd(scene, reference_steps);
    if (reference.size() == 0) {
      ++reference_failures;
      findings.push_back("reference failed: " + scene.describe());
      continue;
    }
    const double length = scene.contactDistance();
    for (const int n_s : stages) {
      std::vector<double> errors;
      for (const int steps : grids) {
        fesd::SimulationOptions options = refinement;
        options.discretization.num_stages = n_s;
        options.discretization.num_elements = elements;
        options.wall_time_budget = budget;
        const fesd::SimulationResult result = ps::simulate(scene, steps, options);
        const bool ok = result.status == fesd::SolveStatus::kSuccess;
        const double error =
            ok ? (result.trajectory.finalState() - reference).norm() / length : INFINITY;
        errors.push_back(error);
        const double position = scene.contact_time * steps / scene.horizon;
        ++runs;
        if (!ok) {
          ++failures;
          findings.push_back("failed: n_s " + std::to_string(n_s) + ", " + std::to_string(steps) +
                             " steps: " + result.message + " (" + scene.describe() + ")");
        }
        std::printf("%d,%d,%zu,%d,%s,%d,%d,%.4f,%s,%d,%.3e,%d,%d,%d,%d,%d,%.3f,%d,%d,%d\n", seed,
                    scene.scene.dimension(), scene.scene.bodies().size(),
                    scene.scene.walls().empty() ? 0 : 1,
                    scene.hasClosedForm() ? "closed_form" : "fine_fesd", n_s, steps,
                    position - static_cast<int>(position), fesd::statusName(result.status).c_str(),
                    ok ? -1 : result.completed_steps, error, result.totals.iterations,
                    result.retried_steps, result.split_steps, result.fixed_step_parts,
                    result.refined_parts, result.totals.wall_seconds, result.predicted_parts,
                    result.located_parts, result.homotopy_parts);
        std::fflush(stdout);
      }
      for (const int i : ps::outliers(errors)) {
        if (!std::isfinite(errors[i])) continue;  // counted as a failure
        ++outlier_count;
        findings.push_back("outlier: n_s " + std::to_string(n_s) + ", " + std::to_string(grids[i]) +
                           " steps, error " + std::to_string(errors[i]) + " (" + scene.describe() +
                           ")");
      }
    }
  }
  std::printf("# runs=%d failed=%d outlier_grids=%d reference_failures=%d\n", runs, failures,
              outlier_count, reference_failures);
  for (const std::string& finding : findings) std::printf("# %s\n", finding.c_str());
  return 0;
}

}  // namespace fesd_bench
