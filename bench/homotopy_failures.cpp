// homotopy-failures: does the homotopy do better continuing after a relaxed NLP that Ipopt did
// not solve (HomotopyOptions::max_consecutive_failures 0), or stopping there (1)? Runs simulations
// and OCPs with both settings; CSV, one line per run.
#include <algorithm>
#include <cstdio>
#include <string>

#include "commands.h"
#include "fesd_trajopt/examples/circle_example.h"
#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd_bench {
namespace {

/// Failed NLPs of some homotopies: how many, and the longest run of them in one homotopy.
struct Failures {
  int failed = 0, longest_run = 0;
  void add(const std::vector<fesd::HomotopyStep>& history) {
    int run = 0;
    for (const fesd::HomotopyStep& step : history) {
      failed += !step.converged;
      run = step.converged ? 0 : run + 1;
      longest_run = std::max(longest_run, run);
    }
  }
};

void printRun(const std::string& problem, const std::string& grid, bool continuing,
              const fesd::MpccReport& totals, const Failures& failures, double error) {
  std::printf("%s,%s,%d,%s,%d,%d,%d,%.3f,%.3g\n", problem.c_str(), grid.c_str(), continuing,
              fesd::statusName(totals.status).c_str(), failures.failed, failures.longest_run,
              totals.iterations, totals.wall_seconds, error);
  std::fflush(stdout);
}

void simulateWith(const std::string& problem, std::shared_ptr<const fesd::DynamicsModel> model,
                  const Eigen::VectorXd& x0, double horizon, int steps, int stages, int elements,
                  const std::vector<Eigen::VectorXd>& controls, const Eigen::VectorXd& exact) {
  for (bool continuing : {true, false}) {
    fesd::SimulationOptions options;
    options.discretization.num_stages = stages;
    options.discretization.num_elements = elements;
    options.homotopy.max_consecutive_failures = continuing ? 0 : 1;
    options.retry_homotopy.max_consecutive_failures = continuing ? 0 : 1;
    fesd::FesdIntegrator integrator(model, options);
    const fesd::SimulationResult result = integrator.simulate(x0, horizon, steps, controls);
    Failures failures;
    for (const auto& history : result.step_histories) failures.add(history);
    printRun(problem,
             "steps=" + std::to_string(steps) + " n_s=" + std::to_string(stages) +
                 " elements=" + std::to_string(elements),
             continuing, result.totals, failures, (result.trajectory.finalState() - exact).norm());
  }
}

}  // namespace

int homotopyFailures(const Arguments& args) {
  const std::vector<int> stages = args.integers("stages", {1, 2, 3, 4});
  const std::vector<int> totals = args.integers("steps", {5, 10, 20, 40});
  const std::vector<int> intervals = args.integers("intervals", {10, 20, 30});
  args.rejectUnused();
  std::printf(
      "problem,grid,continuing,status,failed_nlps,longest_failed_run,iterations,"
      "wall_s,error\n");
  namespace example = fesd::circle_example;
  for (int s : stages) {
    for (int steps : totals) {
      simulateWith("circle", example::model(), example::initialState(), example::horizon(), steps,
                   s, 2, {}, example::exactState(example::horizon()));
    }
  }
  // A pusher driven at 2 m/s into three discs in a line (test_contact_chains.cpp).
  fesd::Scene chain(2);
  chain.bodies() = {{"pusher", 0.5, Eigen::Vector2d(-3.0, 0.0), true},
                    {"first", 0.5, Eigen::Vector2d(0.0, 0.0), false},
                    {"second", 0.5, Eigen::Vector2d(2.0, 0.0), false},
                    {"third", 0.5, Eigen::Vector2d(4.0, 0.0), false}};
  Eigen::VectorXd chain_end(8);
  chain_end << 1.25, 0.0, 2.25, 0.0, 3.25, 0.0, 4.25, 0.0;
  for (int s : stages) {
    for (int steps : totals) {
      simulateWith("chain", chain.model(chain.allPairs()), chain.initialState(), 4.0, steps, s, 2,
                   {Eigen::Vector2d(2.0, 0.0)}, chain_end);
    }
  }
  // The showcase plan (N = 40, 3 elements) re-simulated on the finer grid of its test; the
  // error is the distance from the plan's end state.
  const fesd::OcpDefinition showcase = fesd::manipulation_example::ocp(40);
  fesd::OcpOptions plan_options;
  plan_options.discretization.num_elements = 3;
  const fesd::OcpSolution plan = fesd::OcpSolver(showcase, plan_options).solve();
  simulateWith("showcase-resim", showcase.model, showcase.initial_state, showcase.horizon,
               showcase.num_intervals, 3, 6, plan.trajectory.controls,
               plan.trajectory.finalState());
  for (int n : intervals) {
    for (int elements : {2, 3}) {
      for (bool continuing : {true, false}) {
        fesd::OcpOptions options;
        options.discretization.num_elements = elements;
        options.homotopy.max_consecutive_failures = continuing ? 0 : 1;
        fesd::OcpSolver solver(fesd::manipulation_example::ocp(n), options);
        const fesd::OcpSolution solution = solver.solve();
        Failures failures;
        failures.add(solution.report.history);
        const Eigen::VectorXd& end = solution.trajectory.finalState();
        printRun("showcase", "N=" + std::to_string(n) + " elements=" + std::to_string(elements),
                 continuing, solution.report, failures,
                 (end.tail<2>() - fesd::manipulation_example::objectGoal()).norm());
      }
    }
  }
  return 0;
}

}  // namespace fesd_bench
