// ocp-manipulation: seed 000 Sec. IV-B, the collaborative manipulation OCP. One line of
// key=value pairs per run.
#include <algorithm>
#include <cstdio>
#include <vector>

#include "commands.h"
#include "fesd_trajopt/core/manipulation_example.h"
#include "fesd_trajopt/core/ocp_solver.h"

namespace fesd_bench {

int ocpManipulation(const Arguments& args) {
  const int intervals = args.integer("intervals", 30);
  fesd::OcpOptions options;
  options.discretization.num_elements = args.integer("elements", 3);
  options.discretization.num_stages = args.integer("stages", 2);
  options.discretization.switch_detection = args.flag("fesd", true);
  options.discretization.step_bound = args.number("step-bound", options.discretization.step_bound);
  options.fixed_grid_until_sigma = args.number("fixed-grid-until", options.fixed_grid_until_sigma);
  const int repeat = args.integer("repeat", 1);
  fesd::SimulationOptions fine;
  fine.discretization.num_stages =
      args.integer("resim-stages", options.discretization.num_stages + 1);
  fine.discretization.num_elements =
      args.integer("resim-elements", 2 * options.discretization.num_elements);
  args.rejectUnused();

  const fesd::OcpDefinition ocp = fesd::manipulation_example::ocp(intervals);
  std::vector<double> walls;
  for (int r = 0; r < repeat; ++r) {
    fesd::OcpSolver solver(ocp, options);
    const fesd::OcpSolution solution = solver.solve();
    const fesd::MpccReport& report = solution.report;
    const Eigen::VectorXd& end = solution.trajectory.finalState();
    int contacts = 0, releases = 0;
    for (const fesd::SwitchEvent& event : solution.trajectory.switches) {
      (event.kind == fesd::SwitchEvent::Kind::kContact ? contacts : releases)++;
    }
    const double resim = fesd::resimulationError(ocp, solution, fine);
    walls.push_back(report.wall_seconds);
    std::printf(
        "run=%d status=%s objective=%.6g comp_residual=%.3g object_final_x=%.6f "
        "object_final_y=%.6f n_switches=%zu contacts=%d releases=%d resim_error=%.3g "
        "ipopt_iterations=%d wall_s=%.3f cpu_s=%.3f ipopt_s=%.3f eval_s=%.3f "
        "homotopy_steps=%zu intervals=%d elements=%d stages=%d method=%s\n",
        r, fesd::statusName(solution.status).c_str(), report.objective,
        report.complementarity_residual, end(4), end(5), solution.trajectory.switches.size(),
        contacts, releases, resim, report.iterations, report.wall_seconds, report.cpu_seconds,
        report.ipopt_seconds, report.evaluation_seconds, report.history.size(), intervals,
        options.discretization.num_elements, options.discretization.num_stages,
        options.discretization.switch_detection ? "fesd" : "standard");
    std::fflush(stdout);
  }
  std::sort(walls.begin(), walls.end());
  if (repeat > 1) std::printf("median_wall_s=%.3f runs=%d\n", walls[walls.size() / 2], repeat);
  return 0;
}

}  // namespace fesd_bench
