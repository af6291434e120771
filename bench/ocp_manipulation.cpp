// ocp-manipulation: Pozharskiy et al. 2024 Sec. IV-B, the collaborative manipulation OCP. One line
// of key=value pairs per run.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.h"
#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/ocp/ocp_solver.h"

namespace fesd_bench {
namespace {

/// The state of a trajectory at an element boundary time (every control interval boundary is one).
const Eigen::VectorXd& stateAt(const fesd::Trajectory& trajectory, double time) {
  const auto closest = std::min_element(
      trajectory.times.begin(), trajectory.times.end(),
      [time](double a, double b) { return std::abs(a - time) < std::abs(b - time); });
  return trajectory.states[closest - trajectory.times.begin()];
}

/// Where the re-simulation error comes from: per control interval boundary, the distance of the
/// OCP's state from the fine re-simulation and that of the fine from a twice finer one. Errors
/// made early and amplified by the dynamics grow in both columns alike.
void printDivergence(const fesd::OcpDefinition& ocp, const fesd::OcpSolution& solution,
                     const fesd::SimulationOptions& fine) {
  fesd::SimulationOptions finer = fine;
  finer.discretization.num_elements *= 2;
  std::vector<fesd::Trajectory> simulations;
  for (const fesd::SimulationOptions& options : {fine, finer}) {
    const fesd::SimulationResult result =
        fesd::FesdIntegrator(ocp.model, options)
            .simulate(ocp.initial_state, ocp.horizon, ocp.num_intervals,
                      solution.trajectory.controls);
    if (result.status != fesd::SolveStatus::kSuccess) {
      std::printf("divergence: re-simulation failed: %s\n", result.message.c_str());
      return;
    }
    simulations.push_back(result.trajectory);
  }
  for (const double time : solution.trajectory.interval_times) {
    const Eigen::VectorXd& planned = stateAt(solution.trajectory, time);
    const Eigen::VectorXd& simulated = stateAt(simulations[0], time);
    std::printf("divergence t=%.4f ocp_vs_fine=%.3e fine_vs_finer=%.3e\n", time,
                (planned - simulated).norm(), (simulated - stateAt(simulations[1], time)).norm());
  }
}

/// The BLAS variant tools/with_blas.sh set, or "system".
const char* blasVariant() {
  const char* variant = std::getenv("FESD_BLAS_VARIANT");
  return variant ? variant : "system";
}

/// One line per relaxed NLP (sigma = 0: polishing), with enough digits to compare runs.
void printHistory(const fesd::MpccReport& report) {
  for (const fesd::HomotopyStep& step : report.history) {
    std::printf("history sigma=%.3g iterations=%d residual=%.3e objective=%.12g ipopt=%s\n",
                step.sigma, step.iterations, step.complementarity_residual, step.objective,
                step.ipopt_status.c_str());
  }
}

/// Per control interval boundary: time, state (body positions) and the control that follows.
void printTrajectory(const fesd::Trajectory& trajectory) {
  for (size_t k = 0; k < trajectory.interval_times.size(); ++k) {
    const double time = trajectory.interval_times[k];
    std::printf("trajectory t=%.4f x=", time);
    const Eigen::VectorXd& x = stateAt(trajectory, time);
    for (int i = 0; i < x.size(); ++i) std::printf("%s%.4f", i ? "," : "", x(i));
    if (k < trajectory.controls.size()) {
      std::printf(" u=");
      const Eigen::VectorXd& u = trajectory.controls[k];
      for (int i = 0; i < u.size(); ++i) std::printf("%s%.4f", i ? "," : "", u(i));
    }
    std::printf("\n");
  }
  for (const fesd::SwitchEvent& event : trajectory.switches) {
    std::printf("switch t=%.6f constraint=%d kind=%s\n", event.time, event.constraint,
                fesd::SwitchEvent::kindName(event.kind).c_str());
  }
}

}  // namespace

int ocpManipulation(const Arguments& args) {
  const int intervals = args.integer("intervals", 30);
  fesd::OcpOptions options;
  options.discretization.num_elements = args.integer("elements", 3);
  options.discretization.num_stages = args.integer("stages", 2);
  options.discretization.switch_detection = args.flag("fesd", true);
  options.discretization.step_bound = args.number("step-bound", options.discretization.step_bound);
  options.fixed_grid_until_sigma = args.number("fixed-grid-until", options.fixed_grid_until_sigma);
  options.discretization.pds.step_equilibration = pdsStepEquilibration(args);
  options.discretization.pds.equilibration_big_m =
      args.number("big-m", options.discretization.pds.equilibration_big_m);
  applyHomotopyArguments(args, options.homotopy);
  const int repeat = args.integer("repeat", 1);
  fesd::SimulationOptions fine;
  fine.discretization.num_stages =
      args.integer("resim-stages", options.discretization.num_stages + 1);
  fine.discretization.num_elements =
      args.integer("resim-elements", 2 * options.discretization.num_elements);
  const bool divergence = args.flag("divergence", false);
  const bool history = args.flag("history", false);
  const bool from_plan = startsFromPlan(args);
  options.guess_sigma = args.number("guess-sigma", options.guess_sigma);
  options.guess_early_polish_sigma =
      args.number("guess-early-polish", options.guess_early_polish_sigma);
  const bool print_trajectory = args.flag("trajectory", false);
  args.rejectUnused();

  const fesd::OcpDefinition ocp = fesd::manipulation_example::ocp(intervals);
  const fesd::PushPlan plan = fesd::manipulation_example::plan(intervals);
  std::vector<double> walls;
  for (int r = 0; r < repeat; ++r) {
    fesd::OcpSolver solver(ocp, options);
    const fesd::OcpSolution solution = from_plan ? solver.solve(plan.guess) : solver.solve();
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
        "homotopy_steps=%zu intervals=%d elements=%d stages=%d method=%s start=%s "
        "blas=%s\n",
        r, fesd::statusName(solution.status).c_str(), report.objective,
        report.complementarity_residual, end(4), end(5), solution.trajectory.switches.size(),
        contacts, releases, resim, report.iterations, report.wall_seconds, report.cpu_seconds,
        report.ipopt_seconds, report.evaluation_seconds, report.history.size(), intervals,
        options.discretization.num_elements, options.discretization.num_stages,
        options.discretization.switch_detection ? "fesd" : "standard",
        from_plan ? "plan" : "constant", blasVariant());
    if (history) printHistory(report);
    if (print_trajectory) printTrajectory(solution.trajectory);
    if (divergence) printDivergence(ocp, solution, fine);
    std::fflush(stdout);
  }
  std::sort(walls.begin(), walls.end());
  if (repeat > 1) std::printf("median_wall_s=%.3f runs=%d\n", walls[walls.size() / 2], repeat);
  return 0;
}

}  // namespace fesd_bench
