// ocp-accuracy: what accuracy costs on the manipulation showcase (Pozharskiy et al. 2024 Sec. IV-B;
// the analogue of Nurkanovic et al. 2024 Fig. 13). Each run solves the OCP, then re-simulates its
// optimal controls with a much finer FESD integration; the distance of the two terminal states is
// the accuracy. Solves start from the push plan (--start=plan, as the node does) or the constant
// guess.
#include <cmath>
#include <cstdio>

#include "commands.h"
#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/ocp/ocp_solver.h"

namespace fesd_bench {

int ocpAccuracy(const Arguments& args) {
  const int intervals = args.integer("intervals", 30);
  const std::vector<int> stages = args.integers("stages", {1, 2, 3, 4});
  const std::vector<int> elements = args.integers("elements", {1, 2, 3, 4});
  const std::vector<std::string> methods = args.texts("methods", {"fesd", "standard"});
  const double budget = args.number("budget", 120.0);
  const bool from_plan = startsFromPlan(args);
  fesd::SimulationOptions reference;
  reference.discretization.num_stages = args.integer("reference-stages", 4);
  reference.discretization.num_elements = args.integer("reference-elements", 8);
  args.rejectUnused();

  const fesd::OcpDefinition ocp = fesd::manipulation_example::ocp(intervals);
  const fesd::PushPlan plan = fesd::manipulation_example::plan(intervals);
  std::printf(
      "method,n_s,n_fe,intervals,status,objective,terminal_error,object_goal_error,"
      "ipopt_iterations,cpu_s,wall_s\n");
  for (const std::string& method : methods) {
    for (int n_s : stages) {
      for (int n_fe : elements) {
        fesd::OcpOptions options;
        options.discretization.num_stages = n_s;
        options.discretization.num_elements = n_fe;
        options.discretization.switch_detection = method == "fesd";
        options.homotopy.wall_time_budget = budget;
        fesd::OcpSolver solver(ocp, options);
        const fesd::OcpSolution solution = from_plan ? solver.solve(plan.guess) : solver.solve();
        const fesd::MpccReport& report = solution.report;
        const Eigen::VectorXd& end = solution.trajectory.finalState();
        const double goal_error = std::hypot(end(4), end(5) - 10.0);
        std::printf("%s,%d,%d,%d,%s,%.8g,%.3e,%.3e,%d,%.3f,%.3f\n", method.c_str(), n_s, n_fe,
                    intervals, fesd::statusName(solution.status).c_str(), report.objective,
                    fesd::resimulationError(ocp, solution, reference), goal_error,
                    report.iterations, report.cpu_seconds, report.wall_seconds);
        std::fflush(stdout);
      }
    }
  }
  return 0;
}

}  // namespace fesd_bench
