// ocp-filippov: Nurkanovic et al. 2024 Sec. 5.3, OCP (61) on two sliding surfaces (n_sys = 2). Each
// run solves the OCP, re-simulates its optimal controls with a much finer FESD integration and
// reports the distance of that simulation's end position to the target (the paper's E(T),
// Fig. 13) against CPU time; optionally the element lengths and switch indicators (Fig. 12).
#include <cstdio>
#include <limits>

#include "commands.h"
#include "fesd_trajopt/discretization/stewart_discretization.h"
#include "fesd_trajopt/examples/filippov_examples.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/ocp/ocp_solver.h"

namespace fesd_bench {

int ocpFilippov(const Arguments& args) {
  const std::vector<int> stages = args.integers("stages", {1, 2, 3, 4});
  const std::vector<int> elements = args.integers("elements", {1, 2, 3, 4, 5, 6, 7});
  const std::vector<std::string> methods = args.texts("methods", {"fesd", "standard"});
  const std::string family = args.text("family", "radau");
  if (family != "radau" && family != "gauss") {
    throw std::invalid_argument("--family takes radau or gauss");
  }
  const fesd::StepEquilibration equilibration = stepEquilibration(args);
  const double budget = args.number("budget", 120.0);
  const bool print_steps = args.flag("print-steps", false);
  fesd::SimulationOptions reference;
  reference.discretization.num_stages = args.integer("reference-stages", 4);
  reference.discretization.num_elements = args.integer("reference-elements", 12);
  args.rejectUnused();

  namespace example = fesd::sliding_ocp_example;
  const fesd::OcpDefinition ocp = example::ocp();
  std::printf(
      "method,scheme,n_s,n_fe,status,objective,terminal_error,switches,ipopt_iterations,cpu_s,"
      "wall_s\n");
  for (const std::string& method : methods) {
    for (int n_s : stages) {
      for (int n_fe : elements) {
        fesd::OcpOptions options;
        options.discretization.family = family == "radau" ? fesd::CollocationFamily::kRadauIIA
                                                          : fesd::CollocationFamily::kGaussLegendre;
        options.discretization.num_stages = n_s;
        options.discretization.num_elements = n_fe;
        options.discretization.switch_detection = method == "fesd";
        options.discretization.filippov.step_equilibration = equilibration;
        options.homotopy.wall_time_budget = budget;
        fesd::OcpSolver solver(ocp, options);
        const fesd::OcpSolution solution = solver.solve();
        const fesd::MpccReport& report = solution.report;
        fesd::FesdIntegrator integrator(ocp.model, reference);
        const fesd::SimulationResult simulation = integrator.simulate(
            ocp.initial_state, ocp.horizon, ocp.num_intervals, solution.trajectory.controls);
        const double terminal_error =
            simulation.status == fesd::SolveStatus::kSuccess
                ? (simulation.trajectory.finalState().head(2) - example::targetPosition()).norm()
                : std::numeric_limits<double>::infinity();
        std::printf("%s,%s,%d,%d,%s,%.8g,%.3e,%zu,%d,%.3f,%.3f\n", method.c_str(),
                    fesd::makeTableau(options.discretization.family, n_s).name().c_str(), n_s, n_fe,
                    fesd::statusName(solution.status).c_str(), report.objective, terminal_error,
                    solution.trajectory.switches.size(), report.iterations, report.cpu_seconds,
                    report.wall_seconds);
        if (print_steps) {
          std::printf("# steps");
          for (const fesd::ElementValues& element : solution.trajectory.elements) {
            std::printf(" %.6f", element.step);
          }
          const auto& discretization =
              dynamic_cast<const fesd::StewartDiscretization&>(solver.discretization());
          std::printf("\n# switch_indicators");
          for (double eta : discretization.switchIndicators(report.solution.data())) {
            std::printf(" %.3e", eta);
          }
          std::printf("\n");
        }
        std::fflush(stdout);
      }
    }
  }
  return 0;
}

}  // namespace fesd_bench
