// homotopy-failures: does the homotopy do better continuing after a relaxed NLP that Ipopt did
// not solve (HomotopyOptions::continue_after_failure), or stopping there? Runs simulations and
// OCPs with both settings; CSV, one line per run.
#include <cstdio>
#include <string>

#include "commands.h"
#include "fesd_trajopt/core/circle_example.h"
#include "fesd_trajopt/core/fesd_integrator.h"
#include "fesd_trajopt/core/manipulation_example.h"
#include "fesd_trajopt/core/ocp_solver.h"
#include "fesd_trajopt/core/scene_task.h"

namespace fesd_bench {
namespace {

void printRun(const std::string& problem, const std::string& grid, bool continuing,
              const fesd::MpccReport& totals, int failed, double error) {
  std::printf("%s,%s,%d,%s,%d,%d,%.3f,%.3g\n", problem.c_str(), grid.c_str(), continuing,
              fesd::statusName(totals.status).c_str(), failed, totals.iterations,
              totals.wall_seconds, error);
  std::fflush(stdout);
}

void simulateWith(const std::string& problem, std::shared_ptr<const fesd::DcsModel> model,
                  const Eigen::VectorXd& x0, double horizon, int steps, int stages,
                  const std::vector<Eigen::VectorXd>& controls, const Eigen::VectorXd& exact) {
  for (bool continuing : {true, false}) {
    fesd::SimulationOptions options;
    options.discretization.num_stages = stages;
    options.homotopy.continue_after_failure = continuing;
    options.retry_homotopy.continue_after_failure = continuing;
    fesd::FesdIntegrator integrator(model, options);
    const fesd::SimulationResult result = integrator.simulate(x0, horizon, steps, controls);
    int failed = 0;
    for (const auto& history : result.step_histories) {
      for (const fesd::HomotopyStep& step : history) failed += !step.converged;
    }
    printRun(problem, "steps=" + std::to_string(steps) + " n_s=" + std::to_string(stages),
             continuing, result.totals, failed, (result.trajectory.finalState() - exact).norm());
  }
}

}  // namespace

int homotopyFailures(const Arguments& args) {
  const std::vector<int> stages = args.integers("stages", {1, 2, 3, 4});
  const std::vector<int> totals = args.integers("steps", {5, 10, 20, 40});
  const std::vector<int> intervals = args.integers("intervals", {10, 20, 30});
  args.rejectUnused();
  std::printf("problem,grid,continue_after_failure,status,failed_nlps,iterations,wall_s,error\n");
  namespace example = fesd::circle_example;
  for (int s : stages) {
    for (int steps : totals) {
      simulateWith("circle", example::model(), example::initialState(), example::horizon(), steps,
                   s, {}, example::exactState(example::horizon()));
    }
  }
  // A pusher driven at 2 m/s into three discs in a line (test_contact_chains.cpp).
  fesd::DiscScene chain(2);
  chain.bodies() = {{"pusher", 0.5, Eigen::Vector2d(-3.0, 0.0), true},
                    {"first", 0.5, Eigen::Vector2d(0.0, 0.0), false},
                    {"second", 0.5, Eigen::Vector2d(2.0, 0.0), false},
                    {"third", 0.5, Eigen::Vector2d(4.0, 0.0), false}};
  Eigen::VectorXd chain_end(8);
  chain_end << 1.25, 0.0, 2.25, 0.0, 3.25, 0.0, 4.25, 0.0;
  for (int s : stages) {
    for (int steps : totals) {
      simulateWith("chain", chain.model(chain.allPairs()), chain.initialState(), 4.0, steps, s,
                   {Eigen::Vector2d(2.0, 0.0)}, chain_end);
    }
  }
  for (int n : intervals) {
    for (int elements : {2, 3}) {
      for (bool continuing : {true, false}) {
        fesd::OcpOptions options;
        options.discretization.num_elements = elements;
        options.homotopy.continue_after_failure = continuing;
        fesd::OcpSolver solver(fesd::manipulation_example::ocp(n), options);
        const fesd::OcpSolution solution = solver.solve();
        const Eigen::VectorXd& end = solution.trajectory.finalState();
        printRun("showcase", "N=" + std::to_string(n) + " elements=" + std::to_string(elements),
                 continuing, solution.report, solution.report.failedSteps(),
                 (end.tail<2>() - fesd::manipulation_example::objectGoal()).norm());
      }
    }
  }
  return 0;
}

}  // namespace fesd_bench
