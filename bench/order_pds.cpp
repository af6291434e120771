// order-pds: Pozharskiy et al. 2024 Sec. IV-A, terminal error and switch-time error of Example 1
// against the step size, FESD vs the standard fixed-step method, Radau-IIA with 1..4 stages.
#include <cmath>
#include <functional>
#include <iostream>
#include <limits>
#include <map>

#include "commands.h"
#include "fesd_trajopt/examples/circle_example.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"

namespace fesd_bench {
namespace {

/// Largest distance between an exact switch and the nearest detected switch of the same kind.
double switchTimeError(const std::vector<fesd::SwitchEvent>& events) {
  using Kind = fesd::SwitchEvent::Kind;
  const std::pair<Kind, double> exact[] = {{Kind::kContact, fesd::circle_example::contactTime()},
                                           {Kind::kRelease, fesd::circle_example::releaseTime()}};
  double worst = 0.0;
  for (const auto& [kind, time] : exact) {
    double nearest = std::numeric_limits<double>::infinity();
    for (const fesd::SwitchEvent& event : events) {
      if (event.kind == kind) nearest = std::min(nearest, std::fabs(event.time - time));
    }
    worst = std::max(worst, nearest);
  }
  return worst;
}

/// Where a simulation's Ipopt iterations went: per homotopy level, summed over the steps.
void printProfile(const fesd::SimulationResult& result) {
  std::map<double, std::pair<int, double>, std::greater<double>> levels;
  for (const auto& history : result.step_histories) {
    for (const fesd::HomotopyStep& step : history) {
      levels[step.sigma].first += step.iterations;
      levels[step.sigma].second += step.wall_seconds;
    }
  }
  std::cout << "# steps=" << result.step_histories.size()
            << " iterations=" << result.totals.iterations
            << " ipopt_s=" << result.totals.ipopt_seconds
            << " eval_s=" << result.totals.evaluation_seconds << "\n";
  for (const auto& [sigma, totals] : levels) {
    std::cout << "#   sigma=" << sigma << " iterations=" << totals.first
              << " wall_s=" << totals.second << "\n";
  }
}

}  // namespace

int orderPds(const Arguments& args) {
  const std::vector<int> stages = args.integers("stages", {1, 2, 3, 4});
  const std::vector<int> totals = args.integers("totals", {10, 20, 40, 80, 140, 200, 400});
  const std::vector<std::string> methods = args.texts("methods", {"fesd", "standard"});
  const int elements = args.integer("elements", 2);
  const int repeat = args.integer("repeat", 1);
  const bool profile = args.flag("profile", false);
  fesd::SimulationOptions defaults;
  const double sigma0 = args.number("sigma0", defaults.homotopy.sigma_initial);
  const double kappa = args.number("kappa", defaults.homotopy.sigma_reduction);
  const double big_m = args.number("big-m", defaults.discretization.pds.equilibration_big_m);
  const fesd::PdsStepEquilibration equilibration = pdsStepEquilibration(args);
  const double comp_tol = args.number("comp-tol", defaults.homotopy.complementarity_tolerance);
  const std::string cross = args.text("cross", "sums");
  if (cross != "sums" && cross != "pairs") {
    throw std::invalid_argument("--cross takes sums or pairs");
  }
  const bool polish = args.flag("polish", defaults.homotopy.polish_active_set);
  const fesd::SimulationOptions refinement = steppingArguments(args, false);
  args.rejectUnused();

  std::cout << "method,scheme,n_s,n_fe_total,h,error,switch_time_error,cpu_s,wall_s,status,"
               "ipopt_iterations,predicted_parts,located_parts,homotopy_parts\n";
  const double horizon = fesd::circle_example::horizon();
  for (const std::string& method : methods) {
    if (method != "fesd" && method != "standard") {
      throw std::invalid_argument("unknown method '" + method + "'");
    }
    for (int ns : stages) {
      for (int total : totals) {
        if (total % elements != 0) {
          throw std::invalid_argument("--totals must be multiples of --elements");
        }
        fesd::SimulationOptions options = refinement;
        options.discretization.num_stages = ns;
        options.discretization.num_elements = elements;
        options.discretization.switch_detection = method == "fesd";
        options.homotopy.sigma_initial = sigma0;
        options.homotopy.sigma_reduction = kappa;
        options.discretization.pds.equilibration_big_m = big_m;
        options.discretization.pds.step_equilibration = equilibration;
        options.homotopy.complementarity_tolerance = comp_tol;
        options.homotopy.polish_active_set = polish;
        options.discretization.cross_complementarity =
            cross == "sums" ? fesd::CrossComplementarity::kElementSums
                            : fesd::CrossComplementarity::kStagePairs;
        fesd::FesdIntegrator integrator(fesd::circle_example::model(), options);
        fesd::SimulationResult best;
        for (int r = 0; r < repeat; ++r) {
          fesd::SimulationResult run =
              integrator.simulate(fesd::circle_example::initialState(), horizon, total / elements);
          if (r == 0 || run.totals.wall_seconds < best.totals.wall_seconds) best = run;
        }
        const double error =
            (best.trajectory.finalState() - fesd::circle_example::exactState(horizon)).norm();
        const bool ok = best.status == fesd::SolveStatus::kSuccess;
        std::cout << method << ",radau_iia," << ns << "," << total << "," << horizon / total << ","
                  << error << "," << switchTimeError(best.trajectory.switches) << ","
                  << best.totals.cpu_seconds << "," << best.totals.wall_seconds << ","
                  << (ok ? "ok" : fesd::statusName(best.status)) << "," << best.totals.iterations
                  << "," << best.predicted_parts << "," << best.located_parts << ","
                  << best.homotopy_parts << std::endl;
        if (profile) printProfile(best);
      }
    }
  }
  return 0;
}

}  // namespace fesd_bench
