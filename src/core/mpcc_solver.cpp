#include "fesd_trajopt/core/mpcc_solver.h"

#include <cmath>
#include <sstream>

#include "fesd_trajopt/core/stopwatch.h"
#include "ipopt_session.h"

namespace fesd {

std::string statusName(SolveStatus status) {
  switch (status) {
    case SolveStatus::kSuccess:
      return "success";
    case SolveStatus::kMaxIterations:
      return "max_iterations";
    case SolveStatus::kInfeasible:
      return "infeasible";
    case SolveStatus::kTimeout:
      return "timeout";
    case SolveStatus::kComplementarityNotMet:
      return "complementarity_not_met";
    case SolveStatus::kSolverError:
      return "solver_error";
  }
  return "unknown";
}

void MpccReport::addEffort(const MpccReport& other) {
  iterations += other.iterations;
  wall_seconds += other.wall_seconds;
  cpu_seconds += other.cpu_seconds;
  ipopt_seconds += other.ipopt_seconds;
  evaluation_seconds += other.evaluation_seconds;
}

void MpccReport::accumulate(const MpccReport& other) {
  addEffort(other);
  complementarity_residual = std::max(complementarity_residual, other.complementarity_residual);
}

namespace {

SolveStatus failureStatus(Ipopt::ApplicationReturnStatus status) {
  switch (status) {
    case Ipopt::Maximum_Iterations_Exceeded:
      return SolveStatus::kMaxIterations;
    case Ipopt::Infeasible_Problem_Detected:
      return SolveStatus::kInfeasible;
    case Ipopt::User_Requested_Stop:
    case Ipopt::Maximum_CpuTime_Exceeded:
      return SolveStatus::kTimeout;
    default:
      return SolveStatus::kSolverError;
  }
}

}  // namespace

MpccSolver::MpccSolver(HomotopyOptions options)
    : options_(std::move(options)), session_(std::make_unique<IpoptSession>(options_.ipopt)) {}

MpccSolver::~MpccSolver() = default;

void MpccSolver::polish(RelaxedMpcc& problem, const PrimalDualPoint& converged, double deadline,
                        double last_sigma, MpccReport& report) {
  for (int attempt = 0; attempt < options_.polish_attempts; ++attempt) {
    if (!problem.fixActiveSet(converged.x.data(), attempt - 1)) return;
    PrimalDualPoint point = converged;
    // The dropped product rows are inactive from now on: their multipliers are zero.
    for (int row : problem.complementarityRows()) point.constraint_multipliers[row] = 0.0;
    const NlpOutcome outcome =
        session_->solve(problem, point, deadline, options_.ipopt.warm_start_mu_factor * last_sigma);
    problem.releaseActiveSet();
    const double residual = problem.complementarityResidual(point.x.data());
    report.history.push_back({0.0, outcome.iterations, residual, outcome.objective,
                              IpoptSession::statusName(outcome.status), outcome.wall_seconds});
    report.iterations += outcome.iterations;
    report.evaluation_seconds += outcome.evaluation_seconds;
    report.ipopt_seconds += outcome.wall_seconds - outcome.evaluation_seconds;
    if (IpoptSession::converged(outcome.status) && residual <= report.complementarity_residual) {
      report.solution = point.x;
      report.objective = outcome.objective;
      report.complementarity_residual = residual;
      report.polished = true;
      return;
    }
    if (outcome.status == Ipopt::User_Requested_Stop) return;  // out of time: keep the homotopy's
  }
}

MpccReport MpccSolver::solve(RelaxedMpcc& problem, const std::vector<double>& initial_guess) {
  Stopwatch stopwatch;
  MpccReport report;
  const double deadline =
      std::isfinite(options_.wall_time_budget) ? steadySeconds() + options_.wall_time_budget : 0.0;
  PrimalDualPoint point;
  point.x = initial_guess;
  problem.setVanishingTermsWeight(options_.vanishing_terms_weight);
  const bool smooth = problem.numComplementarities() == 0;
  const int steps = smooth ? 1 : options_.max_steps;
  double sigma = options_.sigma_initial;
  Ipopt::ApplicationReturnStatus last = Ipopt::Internal_Error;
  for (int step = 0; step < steps; ++step) {
    problem.setRelaxation(sigma);
    const NlpOutcome outcome =
        session_->solve(problem, point, deadline, options_.ipopt.warm_start_mu_factor * sigma);
    last = outcome.status;
    const double residual = problem.complementarityResidual(point.x.data());
    report.history.push_back({sigma, outcome.iterations, residual, outcome.objective,
                              IpoptSession::statusName(outcome.status), outcome.wall_seconds});
    report.iterations += outcome.iterations;
    report.evaluation_seconds += outcome.evaluation_seconds;
    report.ipopt_seconds += outcome.wall_seconds - outcome.evaluation_seconds;
    report.solution = point.x;
    report.objective = outcome.objective;
    report.complementarity_residual = residual;
    const bool converged = IpoptSession::converged(outcome.status);
    if (converged && residual <= options_.complementarity_tolerance) {
      report.status = SolveStatus::kSuccess;
      break;
    }
    report.status = converged ? SolveStatus::kComplementarityNotMet : failureStatus(outcome.status);
    if (report.status == SolveStatus::kTimeout) break;
    if (!converged && !options_.continue_after_failure) break;
    sigma *= options_.sigma_reduction;
    if (sigma < options_.minimum_sigma) break;
  }
  if (report.status == SolveStatus::kSuccess && !smooth && options_.polish_active_set) {
    polish(problem, point, deadline, sigma, report);
  }
  std::ostringstream message;
  message << statusName(report.status) << ": " << report.history.size() << " homotopy step(s), "
          << report.iterations << " Ipopt iterations, last NLP " << IpoptSession::statusName(last)
          << ", complementarity residual " << report.complementarity_residual << " (tolerance "
          << options_.complementarity_tolerance << ")"
          << (report.polished ? ", active set polished" : "");
  report.message = message.str();
  report.wall_seconds = stopwatch.wallSeconds();
  report.cpu_seconds = stopwatch.cpuSeconds();
  return report;
}

}  // namespace fesd
