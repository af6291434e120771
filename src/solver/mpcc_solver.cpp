#include "fesd_trajopt/solver/mpcc_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "fesd_trajopt/solver/stopwatch.h"
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
    case SolveStatus::kCancelled:
      return "cancelled";
    case SolveStatus::kAccuracyNotMet:
      return "accuracy_not_met";
    case SolveStatus::kTargetNotReached:
      return "target_not_reached";
  }
  return "unknown";
}

std::string describe(const MpccReport& report, double tolerance) {
  std::ostringstream message;
  message << statusName(report.status) << ": " << report.history.size() << " homotopy step(s), "
          << report.iterations << " Ipopt iterations";
  if (!report.history.empty()) message << ", last NLP " << report.history.back().ipopt_status;
  message << ", complementarity residual " << report.complementarity_residual << " (tolerance "
          << tolerance << ")"
          << (report.polished ? report.b_stationary ? ", active set polished (B-stationary)"
                                                    : ", active set polished"
                              : "");
  return message.str();
}

void MpccReport::addEffort(const MpccReport& other) {
  iterations += other.iterations;
  wall_seconds += other.wall_seconds;
  cpu_seconds += other.cpu_seconds;
  ipopt_seconds += other.ipopt_seconds;
  evaluation_seconds += other.evaluation_seconds;
}

int MpccReport::failedSteps() const {
  int failed = 0;
  for (const HomotopyStep& step : history) failed += !step.converged;
  return failed;
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

/// The objective at x, NaN when it cannot be evaluated (a problem that fails at a point is
/// Ipopt's to report).
double objectiveOrNaN(const NlpProblem& problem, const std::vector<double>& x) {
  try {
    return problem.objective(x.data());
  } catch (const std::exception&) {
    return std::numeric_limits<double>::quiet_NaN();
  }
}

/// Largest violation of the bounds and constraints at x; infinity when they cannot be evaluated.
double constraintViolation(const NlpProblem& problem, const std::vector<double>& x) {
  const int n = problem.numVariables(), m = problem.numConstraints();
  if (static_cast<int>(x.size()) != n) return std::numeric_limits<double>::infinity();
  std::vector<double> x_lower(n), x_upper(n), g_lower(m), g_upper(m), g(m);
  double violation = 0.0;
  try {
    problem.getBounds(x_lower.data(), x_upper.data(), g_lower.data(), g_upper.data());
    problem.constraints(x.data(), g.data());
  } catch (const std::exception&) {
    return std::numeric_limits<double>::infinity();
  }
  for (int i = 0; i < n; ++i)
    violation = std::max({violation, x_lower[i] - x[i], x[i] - x_upper[i]});
  for (int i = 0; i < m; ++i)
    violation = std::max({violation, g_lower[i] - g[i], g[i] - g_upper[i]});
  return std::isnan(violation) ? std::numeric_limits<double>::infinity() : violation;
}

/// Settings shared by every solve of one call: the deadline, the monitor's cancel flag, and
/// Ipopt's obj_scaling_factor (fixed, or the objective at the guess brought to the target size).
IpoptSession::SolveSettings initialSettings(const HomotopyOptions& options,
                                            const NlpProblem& problem,
                                            const std::vector<double>& guess,
                                            double wall_time_budget, const SolveMonitor* monitor) {
  IpoptSession::SolveSettings settings;
  if (monitor != nullptr) settings.cancel = monitor->cancel;
  const double budget = wall_time_budget >= 0.0 ? wall_time_budget : options.wall_time_budget;
  // A deadline of exactly now still stops the first solve at its first iteration.
  if (std::isfinite(budget)) settings.deadline_seconds = steadySeconds() + std::max(budget, 1e-9);
  const double size = std::fabs(objectiveOrNaN(problem, guess));
  settings.objective_scaling = options.objective_scaling > 0.0 ? options.objective_scaling
                               : std::isfinite(size) && size > options.objective_scale_target
                                   ? options.objective_scale_target / size
                                   : 1.0;
  return settings;
}

/// Appends a solved NLP to the report's history and tells the monitor.
void record(MpccReport& report, const HomotopyStep& step, const SolveMonitor* monitor) {
  report.history.push_back(step);
  if (monitor != nullptr && monitor->on_step) monitor->on_step(step);
}

/// While the active set of a polished point is fixed: true if the branch with the pairs it left
/// biactive flipped (HomotopyOptions::branch_check_iterations) offers no lower objective than
/// `objective` from `polished`. Leaves that branch fixed.
bool otherBranchKeepsPoint(IpoptSession& session, const HomotopyOptions& options,
                           RelaxedMpcc& problem, const PrimalDualPoint& polished, double objective,
                           const IpoptSession::SolveSettings& settings, const SolveMonitor* monitor,
                           MpccReport& report) {
  const std::vector<bool> other = problem.flipBiactivePairs(polished.x.data());
  if (other.empty() || !problem.fixGivenActiveSet(other, polished.x.data())) return false;
  PrimalDualPoint point = polished;
  IpoptSession::SolveSettings check = settings;
  check.max_iterations = options.branch_check_iterations;
  const NlpOutcome outcome = session.solve(problem, point, check);
  const bool solved = IpoptSession::converged(outcome.status);
  record(
      report,
      {0.0, outcome.iterations, problem.complementarityResidual(point.x.data()), outcome.objective,
       IpoptSession::statusName(outcome.status), outcome.wall_seconds, solved},
      monitor);
  report.iterations += outcome.iterations;
  report.evaluation_seconds += outcome.evaluation_seconds;
  report.ipopt_seconds += outcome.wall_seconds - outcome.evaluation_seconds;
  return solved && outcome.objective >= objective - 1e-8 * std::max(1.0, std::fabs(objective));
}

/// The polishing stage: keeps `report` as it is unless a polished NLP converges (and, if
/// `require_stationarity`, is B-stationary). Tries the identified active set; after a failed
/// solve the pairs it left biactive flipped (RelaxedMpcc::flipBiactivePairs), else the most
/// ambiguous pairs flipped one at a time; `attempts` solves in all.
void polish(IpoptSession& session, const HomotopyOptions& options, RelaxedMpcc& problem,
            const PrimalDualPoint& converged, double sigma,
            const IpoptSession::SolveSettings& settings, int attempts, bool require_stationarity,
            const SolveMonitor* monitor, MpccReport& report) {
  problem.setBiactiveRule(options.polish_biactive_fraction, sigma);
  // After a failed attempt: its biactive pairs flipped, tried before the next attempt.
  std::vector<bool> biactive_flipped;
  int flip = -1;  // the identified active set, then its most ambiguous pairs flipped in turn
  for (int attempt = 0; attempt < attempts; ++attempt) {
    const bool fixed = biactive_flipped.empty()
                           ? problem.fixActiveSet(converged.x.data(), flip++)
                           : problem.fixGivenActiveSet(biactive_flipped, converged.x.data());
    const bool flipped_biactive = !biactive_flipped.empty();
    biactive_flipped.clear();
    if (!fixed) return;
    PrimalDualPoint point = converged;
    // The dropped product rows are inactive from now on: their multipliers are zero.
    if (point.has_multipliers) {
      for (int row : problem.complementarityRows()) point.constraint_multipliers[row] = 0.0;
    }
    const NlpOutcome outcome = session.solve(problem, point, settings);
    const bool solved = IpoptSession::converged(outcome.status);
    const double descent =
        solved && point.has_multipliers
            ? problem.biactiveDescent(point.x.data(), point.constraint_multipliers.data())
            : std::numeric_limits<double>::infinity();
    if (!solved && !flipped_biactive) biactive_flipped = problem.flipBiactivePairs(point.x.data());
    const double residual = problem.complementarityResidual(point.x.data());
    record(report,
           {0.0, outcome.iterations, residual, outcome.objective,
            IpoptSession::statusName(outcome.status), outcome.wall_seconds, solved},
           monitor);
    report.iterations += outcome.iterations;
    report.evaluation_seconds += outcome.evaluation_seconds;
    report.ipopt_seconds += outcome.wall_seconds - outcome.evaluation_seconds;
    bool stationary = descent <= options.stationarity_tolerance;
    if (solved && !stationary && require_stationarity && options.branch_check_iterations > 0) {
      stationary = otherBranchKeepsPoint(session, options, problem, point, outcome.objective,
                                         settings, monitor, report);
    }
    problem.releaseActiveSet();
    if (solved && residual <= report.complementarity_residual &&
        (stationary || !require_stationarity)) {
      report.solution = point.x;
      report.multipliers = {point.bound_lower_multipliers, point.bound_upper_multipliers,
                            point.constraint_multipliers};
      report.objective = outcome.objective;
      report.complementarity_residual = residual;
      report.polished = true;
      report.polish_sigma = problem.relaxation();
      report.b_stationary = stationary;
      return;
    }
    if (outcome.status == Ipopt::User_Requested_Stop) return;  // out of time: keep the homotopy's
  }
}

/// A polished point is a solution only if its complementarity holds to the tolerance (fixing a
/// side that holds data can leave a pair violated).
bool polishedToTolerance(const MpccReport& report, const HomotopyOptions& options) {
  return report.polished && report.complementarity_residual <= options.complementarity_tolerance;
}

}  // namespace

MpccSolver::MpccSolver(HomotopyOptions options)
    : options_(std::move(options)), session_(std::make_unique<IpoptSession>(options_.ipopt)) {}

MpccSolver::~MpccSolver() = default;

MpccReport MpccSolver::solve(RelaxedMpcc& problem, const std::vector<double>& initial_guess,
                             double sigma_initial, double wall_time_budget) {
  PrimalDualPoint point;
  point.x = initial_guess;
  return run(problem, point, sigma_initial, wall_time_budget);
}

MpccReport MpccSolver::solve(RelaxedMpcc& problem, const MpccReport& previous, double sigma_initial,
                             double wall_time_budget) {
  PrimalDualPoint point;
  point.x = previous.solution;
  const NlpMultipliers& m = previous.multipliers;
  const size_t n = point.x.size();
  if (m.bound_lower.size() == n && m.bound_upper.size() == n &&
      static_cast<int>(m.constraints.size()) == problem.numConstraints()) {
    point.bound_lower_multipliers = m.bound_lower;
    point.bound_upper_multipliers = m.bound_upper;
    point.constraint_multipliers = m.constraints;
    point.has_multipliers = true;
  }
  // The previous active set first: one smooth NLP when the problem is (nearly) the same.
  if (options_.polish_active_set && problem.numComplementarities() > 0 &&
      problem.complementarityResidual(point.x.data()) <= options_.polish_rescue_residual) {
    Stopwatch stopwatch;
    MpccReport report;
    report.solution = point.x;
    report.complementarity_residual = problem.complementarityResidual(point.x.data());
    IpoptSession::SolveSettings settings =
        initialSettings(options_, problem, point.x, wall_time_budget, monitor_);
    settings.warm_start_mu = options_.ipopt.previous_solution_mu;
    settings.warm_start_bound_push = options_.ipopt.previous_solution_bound_push;
    settings.tolerance = options_.ipopt.tolerance;
    settings.max_iterations = options_.polish_iterations;
    // The objective the previous solution was polished with: its vanishing terms' weight.
    problem.setVanishingTermsWeight(options_.vanishing_terms_weight);
    problem.setRelaxation(previous.polish_sigma);
    polish(*session_, options_, problem, point, options_.complementarity_tolerance, settings,
           options_.polish_attempts, true, monitor_, report);
    if (polishedToTolerance(report, options_)) {
      report.status = SolveStatus::kSuccess;
      report.message = "success: polished from the previous solution's active set, " +
                       std::to_string(report.iterations) + " Ipopt iterations";
      report.wall_seconds = stopwatch.wallSeconds();
      report.cpu_seconds = stopwatch.cpuSeconds();
      return report;
    }
    report.wall_seconds = stopwatch.wallSeconds();
    report.cpu_seconds = stopwatch.cpuSeconds();
    MpccReport homotopy =
        run(problem, point, sigma_initial,
            wall_time_budget >= 0.0 ? std::max(0.0, wall_time_budget - report.wall_seconds) : -1.0);
    homotopy.addEffort(report);  // the failed polishing attempts count too
    homotopy.history.insert(homotopy.history.begin(), report.history.begin(), report.history.end());
    return homotopy;
  }
  return run(problem, point, sigma_initial, wall_time_budget);
}

MpccReport MpccSolver::run(RelaxedMpcc& problem, PrimalDualPoint point, double sigma_initial,
                           double wall_time_budget) {
  Stopwatch stopwatch;
  MpccReport report;
  const PrimalDualPoint start = point;
  problem.setVanishingTermsWeight(options_.vanishing_terms_weight);
  IpoptSession::SolveSettings settings =
      initialSettings(options_, problem, point.x, wall_time_budget, monitor_);
  const bool smooth = problem.numComplementarities() == 0;
  const int steps = smooth ? 1 : options_.max_steps;
  double sigma = sigma_initial > 0.0 ? sigma_initial : options_.sigma_initial;
  // The converged relaxed NLP with the smallest residual, for a polishing rescue.
  PrimalDualPoint best;
  double best_residual = std::numeric_limits<double>::infinity(), best_sigma = sigma,
         best_objective = 0.0;
  int consecutive_infeasible = 0;
  // Active sets identified by the last converged relaxation and by the last early polishing.
  std::vector<bool> settled_candidate, polished_set;
  for (int step = 0; step < steps; ++step) {
    problem.setRelaxation(sigma);
    settings.warm_start_mu = options_.ipopt.warm_start_mu_factor * sigma;
    // A smooth NLP is the whole problem: solved once, at the final tolerance.
    settings.tolerance =
        smooth ? options_.ipopt.tolerance
               : std::max(options_.ipopt.tolerance, options_.relaxed_tolerance_factor * sigma);
    const NlpOutcome outcome = session_->solve(problem, point, settings);
    const double residual = problem.complementarityResidual(point.x.data());
    record(report,
           {sigma, outcome.iterations, residual, outcome.objective,
            IpoptSession::statusName(outcome.status), outcome.wall_seconds,
            IpoptSession::converged(outcome.status)},
           monitor_);
    report.iterations += outcome.iterations;
    report.evaluation_seconds += outcome.evaluation_seconds;
    report.ipopt_seconds += outcome.wall_seconds - outcome.evaluation_seconds;
    report.solution = point.x;
    report.multipliers = {point.bound_lower_multipliers, point.bound_upper_multipliers,
                          point.constraint_multipliers};
    report.objective = outcome.objective;
    report.complementarity_residual = residual;
    const bool converged = IpoptSession::converged(outcome.status);
    if (converged && residual < best_residual) {
      best = point;
      best_residual = residual;
      best_sigma = sigma;
      best_objective = outcome.objective;
    }
    if (converged && residual <= options_.complementarity_tolerance) {
      report.status = SolveStatus::kSuccess;
      break;
    }
    // sigma is a product of rounded factors: 1 * 0.1 * 0.1 exceeds 1e-2 by an ulp.
    if (converged && !smooth && options_.polish_active_set &&
        sigma <= options_.early_polish_sigma * (1.0 + 1e-9)) {
      // Polish only an active set that two relaxations in a row identify, once: before it has
      // settled, polishing would fix it, and with it the grid's switch elements, too early.
      problem.setBiactiveRule(options_.polish_biactive_fraction, sigma);
      const std::vector<bool> active_set = problem.identifyActiveSet(point.x.data());
      if (!active_set.empty() && active_set == settled_candidate && active_set != polished_set) {
        polished_set = active_set;
        IpoptSession::SolveSettings polish_settings = settings;
        polish_settings.tolerance = options_.ipopt.tolerance;
        polish_settings.max_iterations = options_.polish_iterations;
        polish(*session_, options_, problem, point, sigma, polish_settings, 1, true, monitor_,
               report);
        if (polishedToTolerance(report, options_)) {
          report.status = SolveStatus::kSuccess;
          break;
        }
      }
      settled_candidate = active_set;
    }
    report.status = converged ? SolveStatus::kComplementarityNotMet : failureStatus(outcome.status);
    if (interrupted(report.status)) break;
    consecutive_infeasible =
        report.status == SolveStatus::kInfeasible ? consecutive_infeasible + 1 : 0;
    if (!converged && (!options_.continue_after_failure ||
                       consecutive_infeasible >= options_.max_consecutive_infeasible)) {
      break;
    }
    sigma *= options_.sigma_reduction;
    if (sigma < options_.minimum_sigma) break;
  }
  if (interrupted(report.status) && !std::isfinite(best_residual) &&
      constraintViolation(problem, start.x) < constraintViolation(problem, point.x)) {
    // Nothing converged: of the start and the interrupted iterate, the more feasible one (a
    // warm start's start is a previous solution, e.g. the fixed-grid stage's).
    best = start;
    best_residual = problem.complementarityResidual(start.x.data());
    best_objective = objectiveOrNaN(problem, start.x);
  }
  if (interrupted(report.status) && std::isfinite(best_residual)) {
    // The interrupted NLP's iterate solves nothing yet: the best converged relaxed NLP is the
    // best iterate there is.
    report.solution = best.x;
    report.multipliers = {best.bound_lower_multipliers, best.bound_upper_multipliers,
                          best.constraint_multipliers};
    report.objective = best_objective;
    report.complementarity_residual = best_residual;
  }
  if (!smooth && options_.polish_active_set) {
    settings.tolerance = options_.ipopt.tolerance;
    if (report.status == SolveStatus::kSuccess && !report.polished) {
      settings.warm_start_mu = options_.ipopt.warm_start_mu_factor * sigma;
      polish(*session_, options_, problem, point, sigma, settings, options_.polish_attempts, false,
             monitor_, report);
    } else if (report.status != SolveStatus::kSuccess && !interrupted(report.status) &&
               best_residual <= options_.polish_rescue_residual) {
      settings.warm_start_mu = options_.ipopt.warm_start_mu_factor * best_sigma;
      report.complementarity_residual = best_residual;
      polish(*session_, options_, problem, best, best_sigma, settings, options_.polish_attempts,
             false, monitor_, report);
      if (polishedToTolerance(report, options_)) report.status = SolveStatus::kSuccess;
    }
  }
  // A stop asked for ends the solve whatever the NLP it reached said (e.g. a rescue polish).
  if (report.status != SolveStatus::kSuccess && monitor_ != nullptr && monitor_->cancelled()) {
    report.status = SolveStatus::kCancelled;
  }
  report.message = describe(report, options_.complementarity_tolerance);
  report.wall_seconds = stopwatch.wallSeconds();
  report.cpu_seconds = stopwatch.cpuSeconds();
  return report;
}

}  // namespace fesd
