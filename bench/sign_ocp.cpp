// sign-ocp: Nurkanovic et al. 2024 Sec. 4.6, OCP (56) from forward simulations of several initial
// values as guesses: the x0 found by FESD and the standard method, with a homotopy or a single
// relaxed NLP at a fixed sigma (no polishing), against the analytic optimum; and (strategy
// "ocp-solver") OcpSolver's two-stage homotopy from the constant guess x0_guess.
#include <cmath>
#include <cstdio>

#include "commands.h"
#include "fesd_trajopt/examples/filippov_examples.h"
#include "fesd_trajopt/ocp/ocp_solver.h"

namespace fesd_bench {

int signOcp(const Arguments& args) {
  const std::vector<std::string> methods = args.texts("methods", {"fesd", "standard"});
  const std::vector<std::string> strategies =
      args.texts("strategies", {"homotopy", "fixed", "ocp-solver"});
  const double fixed_sigma = args.number("fixed-sigma", 1e-15);
  const std::vector<std::string> guesses =
      args.texts("guesses", {"-2.5", "-2", "-1.5", "-1", "-0.5", "0", "0.5", "1", "1.5", "2"});
  args.rejectUnused();

  namespace example = fesd::sign_example;
  std::printf("method,strategy,guess,x0,x0_error,objective,status\n");
  for (const std::string& guess_text : guesses) {
    const double guess = std::stod(guess_text);
    for (const std::string& method : methods) {
      for (const std::string& strategy : strategies) {
        double x0, objective;
        fesd::SolveStatus status;
        if (strategy == "ocp-solver") {
          fesd::OcpOptions options;
          options.discretization = example::discretization(method == "fesd");
          fesd::OcpSolver solver(example::ocp(guess), options);
          const fesd::OcpSolution solution = solver.solve();
          x0 = solution.trajectory.states.front()(0);
          objective = solution.report.objective;
          status = solution.status;
        } else {
          fesd::HomotopyOptions homotopy;
          if (strategy == "fixed") {
            homotopy.sigma_initial = fixed_sigma;
            homotopy.max_steps = 1;
            homotopy.polish_active_set = false;
          } else if (strategy != "homotopy") {
            throw std::invalid_argument("--strategies takes homotopy, fixed and ocp-solver");
          }
          const example::Result result = example::solve(guess, method == "fesd", homotopy);
          x0 = result.initial_state;
          objective = result.objective;
          status = result.status;
        }
        std::printf("%s,%s,%g,%.8f,%.3e,%.8g,%s\n", method.c_str(), strategy.c_str(), guess, x0,
                    std::fabs(x0 - example::optimalInitialState()), objective,
                    fesd::statusName(status).c_str());
        std::fflush(stdout);
      }
    }
  }
  return 0;
}

}  // namespace fesd_bench
