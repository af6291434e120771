#include "fesd_trajopt/ocp/ocp_solver.h"

#include <limits>
#include <stdexcept>

namespace fesd {

namespace {

HomotopyOptions fixedGridHomotopy(const OcpOptions& options) {
  HomotopyOptions stage = options.homotopy;
  stage.minimum_sigma = options.fixed_grid_until_sigma;
  stage.polish_active_set = false;
  return stage;
}

/// The solver's message, and a warning when the trajectory has unresolved switches.
std::string resultMessage(const MpccReport& report, const Trajectory& trajectory) {
  if (trajectory.switchesResolved()) return report.message;
  return report.message + "; " + describeUnresolvedSwitches(trajectory.unresolved_switches);
}

/// From a guess: a first relaxation too tight for it starts over looser (cluttered seeds 106 and
/// 110 ran theirs at sigma 1e-2 to Ipopt's limit and timed out; from 1e-1 both succeed).
HomotopyOptions guessHomotopy(const OcpOptions& options) {
  HomotopyOptions homotopy = options.homotopy;
  homotopy.early_polish_sigma = options.guess_early_polish_sigma;
  homotopy.loosen_failed_first_relaxation = true;
  return homotopy;
}

/// From a plan: one polishing attempt of its active set (when it does not fit, flipping its most
/// ambiguous pairs rarely did: three failed attempts of 100 iterations each before the homotopy
/// on the closed loop's replans), however far its mapped point is from complementarity.
HomotopyOptions planHomotopy(const OcpOptions& options) {
  HomotopyOptions homotopy = guessHomotopy(options);
  homotopy.polish_attempts = 1;
  homotopy.polish_previous_always = true;
  return homotopy;
}

}  // namespace

OcpSolver::OcpSolver(OcpDefinition ocp, OcpOptions options)
    : ocp_(std::move(ocp)),
      options_(std::move(options)),
      discretization_(discretize(ocp_, options_.discretization)),
      solver_(options_.homotopy),
      fixed_grid_solver_(fixedGridHomotopy(options_)),
      guess_solver_(guessHomotopy(options_)),
      plan_solver_(planHomotopy(options_)) {}

void OcpSolver::setMonitor(const SolveMonitor* monitor) {
  for (MpccSolver* solver : {&solver_, &fixed_grid_solver_, &guess_solver_, &plan_solver_}) {
    solver->setMonitor(monitor);
  }
}

std::string startName(OcpStart start, const std::string& guess, const std::string& trajectory) {
  switch (start) {
    case OcpStart::kConstant:
      return "constant";
    case OcpStart::kGuess:
      return guess;
    case OcpStart::kConstantAfterGuess:
      return "constant after a failed solve from the " + guess;
    case OcpStart::kPrevious:
      return "previous solution";
    case OcpStart::kGuessAfterPrevious:
      return guess + " after a failed warm start";
    case OcpStart::kTrajectory:
      return trajectory;
    case OcpStart::kGuessAfterTrajectory:
      return guess + " after a failed solve from the " + trajectory;
  }
  return "unknown";
}

OcpSolution OcpSolver::solve() {
  return solveFromConstant(options_.homotopy.wall_time_budget);
}

OcpSolution OcpSolver::solveFromConstant(double wall_time_budget) {
  if (!discretization_->stepsAreFree() || options_.fixed_grid_until_sigma <= 0.0) {
    return finish(solver_.solve(discretization_->nlp(), discretization_->constantGuess(), -1.0,
                                std::max(0.0, wall_time_budget)),
                  *discretization_);
  }
  // Built on first use (3-5 ms on the showcase): solves from a guess or a previous solution
  // rarely come here.
  if (!fixed_grid_) {
    DiscretizationOptions fixed = options_.discretization;
    fixed.switch_detection = false;
    fixed_grid_ = discretize(ocp_, fixed);
  }
  MpccReport fixed = fixed_grid_solver_.solve(fixed_grid_->nlp(), fixed_grid_->constantGuess(),
                                              -1.0, std::max(0.0, wall_time_budget));
  const double remaining = wall_time_budget - fixed.wall_seconds;
  if (interrupted(fixed.status) || fixed.history.empty()) {
    return finish(std::move(fixed), *fixed_grid_);
  }
  const double sigma = fixed.history.back().sigma * options_.homotopy.sigma_reduction;
  OcpSolution solution =
      finish(solver_.solve(discretization_->nlp(),
                           discretization_->adoptedGuess(*fixed_grid_, fixed.solution), sigma,
                           std::max(0.0, remaining)),
             *discretization_);
  // One homotopy in two stages: report it as such.
  solution.report.history.insert(solution.report.history.begin(), fixed.history.begin(),
                                 fixed.history.end());
  solution.report.addEffort(fixed);
  solution.report.message = describe(solution.report, options_.homotopy.complementarity_tolerance) +
                            " (" + std::to_string(fixed.history.size()) +
                            " step(s) on the fixed grid)";
  solution.message = resultMessage(solution.report, solution.trajectory);
  return solution;
}

OcpSolution OcpSolver::solve(const OcpSolution& previous) {
  if (static_cast<int>(previous.report.solution.size()) != discretization_->nlp().numVariables()) {
    throw std::invalid_argument("OcpSolver: the warm start comes from a different discretisation");
  }
  OcpSolution solution =
      finish(solver_.solve(discretization_->nlp(), previous.report, options_.warm_start_sigma,
                           std::max(0.0, options_.homotopy.wall_time_budget)),
             *discretization_);
  solution.start = OcpStart::kPrevious;
  return solution;
}

OcpSolution OcpSolver::solve(const TrajectoryGuess& guess) {
  return solveFromGuess(guess, options_.homotopy.wall_time_budget);
}

OcpSolution OcpSolver::solveFromPoint(const std::vector<double>& point, double wall_time_budget) {
  return finish(guess_solver_.solve(discretization_->nlp(), point, options_.guess_sigma,
                                    std::max(0.0, wall_time_budget)),
                *discretization_);
}

OcpSolution OcpSolver::solveFromGuess(const TrajectoryGuess& guess, double wall_time_budget) {
  const std::vector<double> point = discretization_->guessFrom(guess);
  const double residual = discretization_->nlp().equalityResidual(point.data());
  OcpSolution from_guess = solveFromPoint(point, wall_time_budget);
  from_guess.start = OcpStart::kGuess;
  from_guess.guess_residual = residual;
  if (from_guess.status == SolveStatus::kSuccess || interrupted(from_guess.status)) {
    return from_guess;
  }
  OcpSolution solution =
      after(from_guess, solveFromConstant(wall_time_budget - from_guess.report.wall_seconds));
  solution.start = OcpStart::kConstantAfterGuess;
  solution.guess_residual = from_guess.guess_residual;
  solution.message = "from the guess: " + statusName(from_guess.status) +
                     "; then from the constant start: " + solution.message;
  return solution;
}

OcpSolution OcpSolver::solve(const OcpSolution& previous, const TrajectoryGuess& fallback) {
  return orFallback(solve(previous), fallback, OcpStart::kGuessAfterPrevious,
                    "from the previous solution");
}

OcpSolution OcpSolver::solve(const Trajectory& trajectory, const TrajectoryGuess& fallback) {
  OcpSolution from_trajectory =
      finish(guess_solver_.solveNearSolution(
                 discretization_->nlp(), discretization_->guessFromTrajectory(trajectory),
                 options_.guess_sigma, std::max(0.0, options_.homotopy.wall_time_budget)),
             *discretization_);
  from_trajectory.start = OcpStart::kTrajectory;
  return orFallback(std::move(from_trajectory), fallback, OcpStart::kGuessAfterTrajectory,
                    "from the trajectory");
}

OcpSolution OcpSolver::solveFromPlan(const Trajectory& plan, double polish_sigma, double sigma,
                                     const TrajectoryGuess& fallback) {
  MpccReport start;
  start.solution = discretization_->guessFromTrajectory(plan);
  start.polish_sigma = polish_sigma;
  // Tight relaxations are as hard for Ipopt as the MPCC: the homotopy resumes no tighter than a
  // warm start's (on the closed loop's replans from 1e-9 every relaxed NLP ran to Ipopt's limit).
  OcpSolution from_plan = finish(
      plan_solver_.solve(discretization_->nlp(), start, std::max(sigma, options_.warm_start_sigma),
                         std::max(0.0, options_.homotopy.wall_time_budget)),
      *discretization_);
  from_plan.start = OcpStart::kTrajectory;
  return orFallback(std::move(from_plan), fallback, OcpStart::kGuessAfterTrajectory,
                    "from the plan");
}

OcpSolution OcpSolver::orFallback(OcpSolution first, const TrajectoryGuess& fallback,
                                  OcpStart fallback_start, const std::string& first_name) {
  if (first.status == SolveStatus::kSuccess || interrupted(first.status)) return first;
  OcpSolution solution = after(first, solveFromGuess(fallback, options_.homotopy.wall_time_budget -
                                                                   first.report.wall_seconds));
  if (solution.start == OcpStart::kGuess) solution.start = fallback_start;
  solution.message =
      first_name + ": " + statusName(first.status) + "; then from the guess: " + solution.message;
  return solution;
}

OcpSolution OcpSolver::after(const OcpSolution& earlier, OcpSolution later) {
  later.report.history.insert(later.report.history.begin(), earlier.report.history.begin(),
                              earlier.report.history.end());
  later.report.addEffort(earlier.report);
  return later;
}

OcpSolution OcpSolver::finish(MpccReport report, const Discretization& source) const {
  OcpSolution solution;
  solution.report = std::move(report);
  solution.status = solution.report.status;
  solution.trajectory = source.extract(solution.report.solution.data(), 0.0,
                                       options_.activity_tolerance, options_.penetration_tolerance);
  solution.message = resultMessage(solution.report, solution.trajectory);
  return solution;
}

SimulationResult resimulate(const OcpDefinition& ocp, const std::vector<Eigen::VectorXd>& controls,
                            const SimulationOptions& fine) {
  return FesdIntegrator(ocp.model, fine)
      .simulate(ocp.initial_state, ocp.horizon, ocp.num_intervals, controls);
}

double resimulationError(const OcpDefinition& ocp, const OcpSolution& solution,
                         const SimulationOptions& fine) {
  const SimulationResult result = resimulate(ocp, solution.trajectory.controls, fine);
  if (result.status != SolveStatus::kSuccess) return std::numeric_limits<double>::infinity();
  return (result.trajectory.finalState() - solution.trajectory.finalState()).norm();
}

}  // namespace fesd
