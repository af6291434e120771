#include "fesd_trajopt/core/fesd_integrator.h"

#include <algorithm>
#include <cmath>
#include <sstream>
#include <stdexcept>

#include "fesd_trajopt/core/stopwatch.h"

namespace fesd {

FesdIntegrator::FesdIntegrator(std::shared_ptr<const DynamicsModel> model,
                               SimulationOptions options)
    : model_(std::move(model)), options_(std::move(options)) {
  if (!model_) throw std::invalid_argument("FesdIntegrator: no model");
}

SimulationResult FesdIntegrator::simulate(const Eigen::VectorXd& x0, double horizon, int num_steps,
                                          const std::vector<Eigen::VectorXd>& controls) {
  if (num_steps < 1) throw std::invalid_argument("FesdIntegrator: num_steps must be >= 1");
  const int nu = model_->controlSize();
  if (!(controls.size() == static_cast<size_t>(num_steps) || controls.size() == 1 ||
        (controls.empty() && nu == 0))) {
    throw std::invalid_argument("FesdIntegrator: give one control per step or a single one");
  }
  Stopwatch stopwatch;
  // A negative budget means none to the solver.
  auto remainingBudget = [&] {
    return std::isfinite(options_.wall_time_budget)
               ? std::max(0.0, options_.wall_time_budget - stopwatch.wallSeconds())
               : -1.0;
  };
  OcpDefinition step_problem;
  step_problem.model = model_;
  step_problem.initial_state = x0;
  step_problem.horizon = horizon / num_steps;
  step_problem.num_intervals = 1;
  const std::unique_ptr<Discretization> discretization_pointer =
      discretize(step_problem, options_.discretization);
  Discretization& discretization = *discretization_pointer;
  MpccSolver solver(options_.homotopy);
  MpccSolver retry_solver(options_.retry_homotopy);

  SimulationResult result;
  result.status = SolveStatus::kSuccess;
  Eigen::VectorXd state = x0;
  std::vector<double> previous_solution;
  for (int step = 0; step < num_steps; ++step) {
    discretization.setInitialState(state);
    if (step > 0) discretization.continueFrom(result.trajectory);
    const Eigen::VectorXd u =
        controls.empty() ? Eigen::VectorXd() : controls[controls.size() == 1 ? 0 : step];
    if (nu > 0) discretization.fixControl(0, u);
    const std::vector<double> guess = step == 0 || !options_.reuse_previous_step
                                          ? discretization.constantGuess({u})
                                          : discretization.translatedGuess(previous_solution);
    MpccReport report = solver.solve(discretization.nlp(), guess, -1.0, remainingBudget());
    if (!report.converged() && report.status != SolveStatus::kTimeout) {
      MpccReport retry = retry_solver.solve(discretization.nlp(), guess, -1.0, remainingBudget());
      retry.addEffort(report);  // both attempts' effort counts
      if (retry.converged()) ++result.retried_steps;
      report = std::move(retry);
    }
    previous_solution = report.solution;
    result.totals.accumulate(report);
    result.step_histories.push_back(report.history);
    Trajectory piece =
        discretization.extract(report.solution.data(), step * step_problem.horizon,
                               options_.activity_tolerance, options_.penetration_tolerance);
    result.trajectory.append(piece);
    state = piece.finalState();
    if (!report.converged()) {
      result.status = report.status;
      result.message = "step " + std::to_string(step) + " of " + std::to_string(num_steps) +
                       " did not converge: " + report.message;
      break;
    }
    ++result.completed_steps;
  }
  classifySwitches(result.trajectory, discretization.activeAt(x0, options_.activity_tolerance),
                   options_.activity_tolerance, options_.penetration_tolerance);
  if (result.status == SolveStatus::kSuccess) {
    std::ostringstream message;
    message << "simulated " << num_steps << " step(s): " << result.totals.iterations
            << " Ipopt iterations, " << result.trajectory.switches.size() << " switch(es)";
    if (result.retried_steps > 0) message << ", " << result.retried_steps << " step(s) retried";
    result.message = message.str();
  }
  if (!result.trajectory.switchesResolved()) {
    result.message += "; " + describeUnresolvedSwitches(result.trajectory.unresolved_switches);
  }
  result.totals.status = result.status;
  result.totals.message = result.message;
  result.totals.wall_seconds = stopwatch.wallSeconds();
  result.totals.cpu_seconds = stopwatch.cpuSeconds();
  return result;
}

}  // namespace fesd
