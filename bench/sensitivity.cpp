// sensitivity: the derivatives of simulations (SimulationOptions::sensitivities) against the
// exact ones and against those of standard time-stepping (Nurkanovic et al. 2024, Sec. 4.5-4.6,
// Fig. 9). --table=sweep: x(T), V(x0) = (x(T) - 5/3)^2 and their derivatives by x0 for
// x' = 2 - sign(x) over a grid of x0, FESD, standard and analytic. --table=order: the error of
// dx(T)/dx0 against the step count on that system and on the spiral (eq. 47), both methods.
// --table=scenes: random push scenes simulated with and without sensitivities: whether they
// are defined, their largest difference from central finite differences where the perturbed
// runs keep their switches, and the wall-time ratio (medians of --repeat runs).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "commands.h"
#include "fesd_trajopt/examples/filippov_examples.h"
#include "fesd_trajopt/examples/push_scenes.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"

namespace fesd_bench {
namespace {

constexpr double kSignHorizon = 2.0, kSignTarget = 5.0 / 3.0;

fesd::SimulationResult simulate(std::shared_ptr<const fesd::DynamicsModel> model,
                                const Eigen::VectorXd& x0, double horizon, int steps, bool fesd,
                                bool sensitivities = true) {
  fesd::SimulationOptions options;
  options.discretization.switch_detection = fesd;
  options.sensitivities = sensitivities;
  return fesd::FesdIntegrator(std::move(model), options).simulate(x0, horizon, steps);
}

int sweepTable(int steps, double from, double to, int points) {
  std::printf("method,x0,x_end,dx_end,value,dvalue,status\n");
  for (int i = 0; i < points; ++i) {
    const double x0 = from + (to - from) * i / (points - 1);
    const double exact = fesd::sign_example::exactState(x0, kSignHorizon);
    std::printf("analytic,%.6f,%.10f,%.10f,%.10f,%.10f,success\n", x0, exact,
                fesd::sign_example::exactSensitivity(x0),
                (exact - kSignTarget) * (exact - kSignTarget),
                2.0 * (exact - kSignTarget) * fesd::sign_example::exactSensitivity(x0));
    for (const bool fesd : {true, false}) {
      const fesd::SimulationResult result = simulate(
          fesd::sign_example::model(), Eigen::VectorXd::Constant(1, x0), kSignHorizon, steps, fesd);
      const double end = result.trajectory.finalState()(0);
      const double derivative = result.sensitivities.defined_steps == steps
                                    ? result.sensitivities.states.back()(0, 0)
                                    : NAN;
      std::printf("%s,%.6f,%.10f,%.10f,%.10f,%.10f,%s\n", fesd ? "fesd" : "standard", x0, end,
                  derivative, (end - kSignTarget) * (end - kSignTarget),
                  2.0 * (end - kSignTarget) * derivative, fesd::statusName(result.status).c_str());
      std::fflush(stdout);
    }
  }
  return 0;
}

int orderTable(const std::vector<int>& grids) {
  std::printf("system,method,steps,step,state_error,sensitivity_error,status\n");
  struct System {
    const char* name;
    std::shared_ptr<const fesd::DynamicsModel> model;
    Eigen::VectorXd x0;
    double horizon;
    Eigen::VectorXd end;
    Eigen::MatrixXd derivative;
  };
  const double sign_x0 = -0.77;
  const Eigen::Vector2d spiral_x0 = fesd::spiral_example::initialState();
  const double spiral_horizon = fesd::spiral_example::horizon();
  const System systems[] = {
      {"two_minus_sign", fesd::sign_example::model(), Eigen::VectorXd::Constant(1, sign_x0),
       kSignHorizon,
       Eigen::VectorXd::Constant(1, fesd::sign_example::exactState(sign_x0, kSignHorizon)),
       Eigen::MatrixXd::Constant(1, 1, fesd::sign_example::exactSensitivity(sign_x0))},
      {"spiral", fesd::spiral_example::model(), spiral_x0, spiral_horizon,
       fesd::spiral_example::exactState(spiral_horizon),
       fesd::spiral_example::exactSensitivity(spiral_x0, spiral_horizon)}};
  for (const System& system : systems) {
    for (const bool fesd : {true, false}) {
      for (const int steps : grids) {
        const fesd::SimulationResult result =
            simulate(system.model, system.x0, system.horizon, steps, fesd);
        const bool defined = result.sensitivities.defined_steps == steps;
        const double sensitivity_error =
            defined ? (result.sensitivities.states.back().leftCols(system.x0.size()) -
                       system.derivative)
                              .norm() /
                          system.derivative.norm()
                    : NAN;
        std::printf("%s,%s,%d,%.6e,%.6e,%.6e,%s\n", system.name, fesd ? "fesd" : "standard", steps,
                    system.horizon / steps,
                    (result.trajectory.finalState() - system.end).norm() / system.end.norm(),
                    sensitivity_error, fesd::statusName(result.status).c_str());
        std::fflush(stdout);
      }
    }
  }
  return 0;
}

double medianWall(const fesd::push_scenes::PushScene& scene, int steps, bool sensitivities,
                  int repeat) {
  fesd::SimulationOptions options;
  options.sensitivities = sensitivities;
  std::vector<double> walls;
  for (int r = 0; r < repeat; ++r) {
    walls.push_back(fesd::push_scenes::simulate(scene, steps, options).totals.wall_seconds);
  }
  std::sort(walls.begin(), walls.end());
  return walls[walls.size() / 2];
}

/// The largest difference between the sensitivities of the end state by x0 and central
/// differences of the simulation, over the columns whose perturbed runs keep every element and
/// switch (NaN when none does); `valid` counts those columns.
double finiteDifferenceError(const fesd::push_scenes::PushScene& scene, int steps,
                             const fesd::SimulationResult& result, int& valid) {
  fesd::SimulationOptions options;
  const double h = 1e-5;
  const Eigen::VectorXd x0 = scene.initialState();
  double largest = NAN;
  valid = 0;
  const int dimension = scene.scene.dimension();
  for (int d = 0; d < x0.size(); ++d) {
    fesd::push_scenes::PushScene plus = scene, minus = scene;
    for (auto* perturbed : {&plus, &minus}) {
      perturbed->scene.bodies()[d / dimension].position(d % dimension) +=
          perturbed == &plus ? h : -h;
    }
    const fesd::SimulationResult up = fesd::push_scenes::simulate(plus, steps, options);
    const fesd::SimulationResult down = fesd::push_scenes::simulate(minus, steps, options);
    // Valid where the perturbed runs are the same discrete map: the same elements (no part
    // refined or split differently) and every switch at the same element boundary.
    const auto same_switches = [&](const fesd::SimulationResult& other) {
      if (other.status != fesd::SolveStatus::kSuccess ||
          other.trajectory.elements.size() != result.trajectory.elements.size() ||
          other.trajectory.switches.size() != result.trajectory.switches.size()) {
        return false;
      }
      for (size_t i = 0; i < other.trajectory.switches.size(); ++i) {
        const fesd::SwitchEvent &a = other.trajectory.switches[i],
                                &b = result.trajectory.switches[i];
        if (a.kind != b.kind || a.constraint != b.constraint || a.element != b.element)
          return false;
      }
      return true;
    };
    if (!same_switches(up) || !same_switches(down)) continue;
    ++valid;
    const Eigen::VectorXd difference =
        (up.trajectory.finalState() - down.trajectory.finalState()) / (2.0 * h);
    const double error =
        (difference - result.sensitivities.states.back().col(d)).cwiseAbs().maxCoeff();
    largest = std::isnan(largest) ? error : std::max(largest, error);
  }
  return largest;
}

int scenesTable(int first_seed, int scenes, int steps, int repeat) {
  std::printf(
      "seed,bodies,wall,status,defined,switches,fd_columns,fd_error,wall_s,wall_s_with,ratio,"
      "undefined_reason\n");
  for (int seed = first_seed; seed < first_seed + scenes; ++seed) {
    const fesd::push_scenes::PushScene scene = fesd::push_scenes::randomPushScene(seed);
    fesd::SimulationOptions options;
    options.sensitivities = true;
    const fesd::SimulationResult result = fesd::push_scenes::simulate(scene, steps, options);
    const bool defined = result.sensitivities.defined_steps == steps;
    int valid = 0;
    const double fd_error = defined ? finiteDifferenceError(scene, steps, result, valid) : NAN;
    const double without = medianWall(scene, steps, false, repeat);
    const double with = medianWall(scene, steps, true, repeat);
    std::printf("%d,%zu,%d,%s,%d,%zu,%d,%.3e,%.5f,%.5f,%.3f,\"%s\"\n", seed,
                scene.scene.bodies().size(), scene.scene.walls().empty() ? 0 : 1,
                fesd::statusName(result.status).c_str(), defined ? 1 : 0,
                result.trajectory.switches.size(), valid, fd_error, without, with, with / without,
                result.sensitivities.why_undefined.c_str());
    std::fflush(stdout);
  }
  return 0;
}

}  // namespace

int sensitivity(const Arguments& args) {
  const std::string table = args.text("table", "sweep");
  const int steps = args.integer("steps", 25);
  const int points = args.integer("points", 121);
  const std::vector<int> grids = args.integers("grids", {4, 8, 16, 32, 64, 128, 256});
  const int first_seed = args.integer("first-seed", 0);
  const int scenes = args.integer("scenes", 24);
  const int repeat = args.integer("repeat", 5);
  args.rejectUnused();
  if (table == "sweep") return sweepTable(steps, -2.0, 1.0, points);
  if (table == "order") return orderTable(grids);
  if (table == "scenes") return scenesTable(first_seed, scenes, steps, repeat);
  std::fprintf(stderr, "--table takes sweep, order or scenes\n");
  return 2;
}

}  // namespace fesd_bench
