// fesd_circle_example: simulates Pozharskiy et al. 2024, Example 1 with the FESD integrator and
// prints the trajectory's end point, the detected switches against the exact ones, and solver
// statistics.
#include <cmath>
#include <cstdio>
#include <exception>
#include <string>

#include "fesd_trajopt/examples/circle_example.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"

namespace {

int run(int stages, int steps, int elements) {
  namespace example = fesd::circle_example;
  fesd::SimulationOptions options;
  options.discretization.num_stages = stages;
  options.discretization.num_elements = elements;
  fesd::FesdIntegrator integrator(example::model(), options);
  const fesd::SimulationResult result =
      integrator.simulate(example::initialState(), example::horizon(), steps);
  const Eigen::VectorXd& end = result.trajectory.finalState();
  const Eigen::Vector2d exact = example::exactState(example::horizon());
  std::printf(
      "FESD integrator, Pozharskiy et al. 2024 Example 1: xdot = (x2, -x1 + lambda), 0 <= x2 + 1 "
      "_|_ lambda >= "
      "0\n");
  std::printf("  Radau-IIA, %d stage(s); %d steps x %d elements over T = %.6f\n", stages, steps,
              elements, example::horizon());
  std::printf("  status:        %s (%s)\n", fesd::statusName(result.status).c_str(),
              result.message.c_str());
  std::printf("  x(T):          (%.12f, %.12f)\n", end(0), end(1));
  std::printf("  exact x(T):    (%.12f, %.12f)   error %.3e\n", exact(0), exact(1),
              (end - exact).norm());
  const double exact_times[] = {example::contactTime(), example::releaseTime()};
  for (size_t i = 0; i < result.trajectory.switches.size(); ++i) {
    const fesd::SwitchEvent& event = result.trajectory.switches[i];
    std::printf("  switch:        %-7s of constraint %d at t = %.12f",
                fesd::SwitchEvent::kindName(event.kind).c_str(), event.constraint, event.time);
    if (i < 2)
      std::printf("   (exact %.12f, error %.1e)", exact_times[i],
                  std::fabs(event.time - exact_times[i]));
    std::printf("\n");
  }
  std::printf("  solver:        %d Ipopt iterations, complementarity residual %.1e\n",
              result.totals.iterations, result.totals.complementarity_residual);
  std::printf("  time:          %.3f s wall, %.3f s CPU (Ipopt %.3f s, our evaluations %.3f s)\n",
              result.totals.wall_seconds, result.totals.cpu_seconds, result.totals.ipopt_seconds,
              result.totals.evaluation_seconds);
  return result.status == fesd::SolveStatus::kSuccess ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc > 1 && std::string(argv[1]) == "--help") {
    std::printf("usage: fesd_circle_example [stages=4] [steps=10] [elements_per_step=2]\n");
    return 0;
  }
  try {
    return run(argc > 1 ? std::stoi(argv[1]) : 4, argc > 2 ? std::stoi(argv[2]) : 10,
               argc > 3 ? std::stoi(argv[3]) : 2);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "fesd_circle_example: %s\n", error.what());
    return 2;
  }
}
