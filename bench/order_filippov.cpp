// order-filippov: Nurkanovic et al. 2024 Sec. 4.4, terminal error of example (47) against the step
// size, FESD vs the standard fixed-step method, Radau-IIA and Gauss-Legendre.
#include <cmath>
#include <iostream>
#include <limits>

#include "commands.h"
#include "fesd_trajopt/examples/filippov_examples.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"

namespace fesd_bench {

int orderFilippov(const Arguments& args) {
  const std::vector<int> radau_stages = args.integers("radau-stages", {1, 2, 3});
  const std::vector<int> gauss_stages = args.integers("gauss-stages", {1, 2});
  const std::vector<int> totals = args.integers("totals", {16, 24, 32, 48, 64, 96, 128});
  const std::vector<std::string> methods = args.texts("methods", {"fesd", "standard"});
  const int elements = args.integer("elements", 2);
  fesd::SimulationOptions defaults;
  const double kappa = args.number("kappa", defaults.homotopy.sigma_reduction);
  const fesd::StepEquilibration equilibration = stepEquilibration(args);
  const double relaxation = args.number("equilibration-relaxation",
                                        defaults.discretization.filippov.equilibration_relaxation);
  const fesd::SimulationOptions refinement = steppingArguments(args, false);
  args.rejectUnused();

  namespace example = fesd::spiral_example;
  const double horizon = example::horizon();
  std::cout << "method,scheme,n_s,n_fe_total,h,error,switch_time_error,cpu_s,wall_s,status,"
               "ipopt_iterations,predicted_parts,located_parts,homotopy_parts\n";
  for (const std::string& method : methods) {
    if (method != "fesd" && method != "standard") {
      throw std::invalid_argument("unknown method '" + method + "'");
    }
    for (const auto& [family, stages] :
         {std::make_pair(fesd::CollocationFamily::kRadauIIA, radau_stages),
          std::make_pair(fesd::CollocationFamily::kGaussLegendre, gauss_stages)}) {
      for (int ns : stages) {
        for (int total : totals) {
          if (total % elements != 0) {
            throw std::invalid_argument("--totals must be multiples of --elements");
          }
          fesd::SimulationOptions options = refinement;
          options.discretization.family = family;
          options.discretization.num_stages = ns;
          options.discretization.num_elements = elements;
          options.discretization.switch_detection = method == "fesd";
          options.discretization.filippov.step_equilibration = equilibration;
          options.discretization.filippov.equilibration_relaxation = relaxation;
          options.homotopy.sigma_reduction = kappa;
          fesd::FesdIntegrator integrator(example::model(), options);
          const fesd::SimulationResult result =
              integrator.simulate(example::initialState(), horizon, total / elements);
          const double error =
              (result.trajectory.finalState() - example::exactState(horizon)).norm();
          double switch_error = std::numeric_limits<double>::infinity();
          for (const fesd::SwitchEvent& event : result.trajectory.switches) {
            switch_error = std::min(switch_error, std::fabs(event.time - example::switchTime()));
          }
          const bool ok = result.status == fesd::SolveStatus::kSuccess;
          std::cout << method << "," << fesd::makeTableau(family, ns).name() << "," << ns << ","
                    << total << "," << horizon / total << "," << error << "," << switch_error << ","
                    << result.totals.cpu_seconds << "," << result.totals.wall_seconds << ","
                    << (ok ? "ok" : fesd::statusName(result.status)) << ","
                    << result.totals.iterations << "," << result.predicted_parts << ","
                    << result.located_parts << "," << result.homotopy_parts << std::endl;
        }
      }
    }
  }
  return 0;
}

}  // namespace fesd_bench
