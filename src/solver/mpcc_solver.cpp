#include "fesd_trajopt/solver/mpcc_solver.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <utility>
#include <vector>

#include "fesd_trajopt/solver/lpec.h"
#include "fesd_trajopt/solver/square_newton.h"
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

std::string methodName(MpccMethod method) {
  return method == MpccMethod::kActiveSet ? "active_set" : "homotopy";
}

bool parseMethod(const std::string& name, MpccMethod& method) {
  if (name == "homotopy") {
    method = MpccMethod::kHomotopy;
  } else if (name == "active_set") {
    method = MpccMethod::kActiveSet;
  } else {
    return false;
  }
  return true;
}

std::string describe(const MpccReport& report, double tolerance) {
  std::ostringstream message;
  message << statusName(report.status) << ": " << report.history.size() << " homotopy step(s), "
          << report.iterations << " Ipopt iterations";
  if (!report.history.empty()) message << ", last NLP " << report.history.back().ipopt_status;
  message << ", complementarity residual " << report.complementarity_residual << " (tolerance "
          << tolerance << ")"
          << (report.polished ? report.certified ? ", active set polished (B-stationary, certified)"
                                : report.b_stationary ? ", active set polished (B-stationary)"
                                                      : ", active set polished"
                              : "");
  if (!report.certificate.empty() && !report.certified) message << "; " << report.certificate;
  return message.str();
}

void MpccReport::addEffort(const MpccReport& other) {
  iterations += other.iterations;
  wall_seconds += other.wall_seconds;
  cpu_seconds += other.cpu_seconds;
  ipopt_seconds += other.ipopt_seconds;
  evaluation_seconds += other.evaluation_seconds;
  branch_nlps += other.branch_nlps;
  lpecs += other.lpecs;
  lpec_seconds += other.lpec_seconds;
}

int MpccReport::relaxedNlps() const {
  int relaxed = 0;
  for (const HomotopyStep& step : history) relaxed += step.sigma > 0.0;
  return relaxed;
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

/// Appends a polishing (branch NLP) solve to the report and counts its effort.
void recordBranchNlp(MpccReport& report, const NlpOutcome& outcome, double residual, bool solved,
                     const SolveMonitor* monitor) {
  record(report,
         {0.0, outcome.iterations, residual, outcome.objective,
          IpoptSession::statusName(outcome.status), outcome.wall_seconds, solved},
         monitor);
  report.iterations += outcome.iterations;
  report.evaluation_seconds += outcome.evaluation_seconds;
  report.ipopt_seconds += outcome.wall_seconds - outcome.evaluation_seconds;
  ++report.branch_nlps;
}

/// What the branch with a polished point's biactive pairs flipped says of the point.
enum class BranchCheck {
  kKeepsPoint,  ///< it offers no lower objective: B-stationary on both branches
  kLower,       ///< it offers a lower objective (or there is no such branch to solve)
  kNotSolved,   ///< its NLP did not solve within branch_check_iterations: nothing shown
};

/// While the active set of a polished point is fixed: solves the branch with the pairs it left
/// biactive flipped (HomotopyOptions::branch_check_iterations) from `polished` and compares its
/// objective with `objective`. Leaves that branch fixed.
BranchCheck checkOtherBranch(IpoptSession& session, const HomotopyOptions& options,
                             RelaxedMpcc& problem, const PrimalDualPoint& polished,
                             double objective, const IpoptSession::SolveSettings& settings,
                             const SolveMonitor* monitor, MpccReport& report) {
  const std::vector<bool> other = problem.flipBiactivePairs(polished.x.data());
  if (other.empty() || !problem.fixGivenActiveSet(other, polished.x.data())) {
    return BranchCheck::kLower;
  }
  PrimalDualPoint point = polished;
  IpoptSession::SolveSettings check = settings;
  check.max_iterations = options.branch_check_iterations;
  const NlpOutcome outcome = session.solve(problem, point, check);
  const bool solved = IpoptSession::converged(outcome.status);
  recordBranchNlp(report, outcome, problem.complementarityResidual(point.x.data()), solved,
                  monitor);
  if (!solved) return BranchCheck::kNotSolved;
  return outcome.objective >= objective - 1e-8 * std::max(1.0, std::fabs(objective))
             ? BranchCheck::kKeepsPoint
             : BranchCheck::kLower;
}

/// What phase II found at a branch NLP's solution: its last LPEC.
struct Certification {
  bool known = false;  ///< an LPEC was solved
  bool certified = false;
  double value = std::numeric_limits<double>::quiet_NaN(), radius = 0.0;
  std::string message;
};

/// Phase II of the active-set method, at a solved branch NLP whose active set is fixed: LPECs in
/// a trust region, each certifying B-stationarity or proposing a branch; that branch's NLP,
/// solved from the point, becomes the point when it lowers the objective, else the radius is
/// halved; at most `branch_changes` branch NLPs (0: the certificate only). `point` and
/// `objective` end as the last accepted branch's.
Certification certifyOrImprove(IpoptSession& session, const HomotopyOptions& options,
                               RelaxedMpcc& problem, PrimalDualPoint& point, double& objective,
                               int branch_changes, const IpoptSession::SolveSettings& settings,
                               const SolveMonitor* monitor, MpccReport& report) {
  Certification certification;
  double radius = options.lpec_radius;
  int halvings = 0, changes = 0;
  auto lpec = std::make_unique<Lpec>(problem, point.x, point.constraint_multipliers,
                                     options.lpec_tolerance);
  while (!(settings.deadline_seconds > 0.0 && steadySeconds() > settings.deadline_seconds)) {
    LpecBudget budget;
    budget.bound_only = branch_changes == 0;  // a certificate only: the multipliers' bound
    if (settings.deadline_seconds > 0.0)
      budget.seconds = settings.deadline_seconds - steadySeconds();
    const LpecResult result = lpec->solve(radius, budget);
    ++report.lpecs;
    report.lpec_seconds += result.seconds;
    certification.message = result.message;
    certification.radius = radius;
    if (!result.solved) break;
    certification.known = true;
    certification.certified = result.certified;
    certification.value = result.value;
    if (result.certified || changes >= branch_changes ||
        !problem.fixGivenActiveSet(result.left_is_zero, point.x.data())) {
      break;
    }
    ++changes;
    PrimalDualPoint trial = point;
    if (trial.has_multipliers) {
      for (int row : problem.complementarityRows()) trial.constraint_multipliers[row] = 0.0;
    }
    const NlpOutcome outcome = session.solve(problem, trial, settings);
    const bool solved = IpoptSession::converged(outcome.status);
    const double residual = problem.complementarityResidual(trial.x.data());
    recordBranchNlp(report, outcome, residual, solved, monitor);
    if (solved && residual <= options.complementarity_tolerance &&
        outcome.objective < objective - 1e-9 * std::max(1.0, std::fabs(objective))) {
      point = std::move(trial);
      objective = outcome.objective;
      radius = options.lpec_radius;
      halvings = 0;
      lpec = std::make_unique<Lpec>(problem, point.x, point.constraint_multipliers,
                                    options.lpec_tolerance);
      continue;
    }
    if (outcome.status == Ipopt::User_Requested_Stop || ++halvings > options.lpec_radius_halvings) {
      break;
    }
    radius *= 0.5;
  }
  return certification;
}

/// True when `point` (with multipliers) meets the KKT conditions of `problem` as it is bounded now
/// to `tolerance` (dual residual relative to max(1, |grad f|_inf)): the solution of an unchanged
/// problem, which Ipopt would push off its bounds and re-centre (12 iterations on the showcase).
bool solvesAlready(const NlpProblem& problem, const PrimalDualPoint& point, double tolerance) {
  const int n = problem.numVariables(), m = problem.numConstraints();
  if (!point.has_multipliers || static_cast<int>(point.x.size()) != n ||
      static_cast<int>(point.constraint_multipliers.size()) != m ||
      static_cast<int>(point.bound_lower_multipliers.size()) != n ||
      static_cast<int>(point.bound_upper_multipliers.size()) != n) {
    return false;
  }
  if (constraintViolation(problem, point.x) > tolerance) return false;
  std::vector<double> x_lower(n), x_upper(n), g_lower(m), g_upper(m), g(m), gradient(n);
  problem.getBounds(x_lower.data(), x_upper.data(), g_lower.data(), g_upper.data());
  problem.constraints(point.x.data(), g.data());
  problem.objectiveGradient(point.x.data(), gradient.data());
  double scale = 1.0;
  for (double d : gradient) scale = std::max(scale, std::fabs(d));
  const std::vector<double> dual =
      lagrangianGradient(problem, point.x.data(), point.constraint_multipliers.data());
  const auto gap = [](double bound, double value) {
    return std::fabs(bound) >= 1e19 ? 1.0 : std::fabs(value - bound);  // NlpProblem's infinity
  };
  for (int i = 0; i < m; ++i) {
    const double lambda = point.constraint_multipliers[i];
    // Lagrangian f + lambda^T g: lambda < 0 pushes against the lower bound, > 0 the upper one.
    if (std::max(-lambda, 0.0) * gap(g_lower[i], g[i]) > tolerance ||
        std::max(lambda, 0.0) * gap(g_upper[i], g[i]) > tolerance) {
      return false;
    }
  }
  for (int j = 0; j < n; ++j) {
    const double x = point.x[j];
    if (x_lower[j] == x_upper[j]) continue;  // a parameter to Ipopt: no condition
    const double z_lower = point.bound_lower_multipliers[j],
                 z_upper = point.bound_upper_multipliers[j];
    if (z_lower < -tolerance || z_upper < -tolerance || z_lower * gap(x_lower[j], x) > tolerance ||
        z_upper * gap(x_upper[j], x) > tolerance ||
        std::fabs(dual[j] - z_lower + z_upper) > tolerance * scale) {
      return false;
    }
  }
  return true;
}

/// The polishing stage: keeps `report` as it is unless a polished NLP converges (and, if
/// `require_stationarity`, is B-stationary). Tries the identified active set; after a failed
/// solve the pairs it left biactive flipped (RelaxedMpcc::flipBiactivePairs), else the most
/// ambiguous pairs flipped one at a time; `attempts` solves in all. With the active-set method,
/// a solved branch NLP goes through phase II (certifyOrImprove), whose LPEC judges stationarity.
void polish(IpoptSession& session, const HomotopyOptions& options, RelaxedMpcc& problem,
            const PrimalDualPoint& converged, double sigma,
            const IpoptSession::SolveSettings& settings, int attempts, bool require_stationarity,
            const SolveMonitor* monitor, MpccReport& report, bool accept_solved_start = false,
            std::vector<double>* unsolved_iterate = nullptr) {
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
    // A warm start from the solution of the same problem is that solution: no Ipopt iteration.
    const NlpOutcome outcome =
        accept_solved_start && attempt == 0 &&
                solvesAlready(problem, point, options.solved_start_tolerance)
            ? NlpOutcome{Ipopt::Solve_Succeeded, 0, problem.objective(point.x.data()), 0.0, 0.0}
            : session.solve(problem, point, settings);
    const bool solved = IpoptSession::converged(outcome.status);
    // Handed on only if it (nearly) solves its branch's rows: a stalled polish, not a failed one.
    if (!solved && attempt == 0 && unsolved_iterate != nullptr &&
        constraintViolation(problem, point.x) <= options.ipopt.near_solution_violation) {
      *unsolved_iterate = point.x;
    }
    double objective = outcome.objective;
    if (!solved && !flipped_biactive) biactive_flipped = problem.flipBiactivePairs(point.x.data());
    double residual = problem.complementarityResidual(point.x.data());
    recordBranchNlp(report, outcome, residual, solved, monitor);
    // Every solved branch gets its LPEC; only the active-set method follows its branches and
    // judges stationarity by it (the homotopy's decisions, and so its bits, stay as they were).
    const bool active_set = options.method == MpccMethod::kActiveSet;
    Certification certification;
    if (solved && residual <= options.complementarity_tolerance) {
      certification =
          certifyOrImprove(session, options, problem, point, objective,
                           active_set ? options.max_branch_changes : 0, settings, monitor, report);
      residual = problem.complementarityResidual(point.x.data());
    }
    bool stationary = certification.certified;
    // Kept although B-stationarity was not shown: a branch check that did not solve, where the
    // options accept that.
    bool unrefuted = false;
    if (!active_set || !certification.known) {
      const double descent =
          solved && point.has_multipliers
              ? problem.biactiveDescent(point.x.data(), point.constraint_multipliers.data())
              : std::numeric_limits<double>::infinity();
      stationary = descent <= options.stationarity_tolerance;
      if (solved && !stationary && require_stationarity && options.branch_check_iterations > 0) {
        const BranchCheck check = checkOtherBranch(session, options, problem, point, objective,
                                                   settings, monitor, report);
        stationary = check == BranchCheck::kKeepsPoint;
        unrefuted = check == BranchCheck::kNotSolved && options.accept_unsolved_branch_check;
      }
    }
    problem.releaseActiveSet();
    if (solved && residual <= report.complementarity_residual &&
        (stationary || unrefuted || !require_stationarity)) {
      report.solution = point.x;
      report.multipliers = {point.bound_lower_multipliers, point.bound_upper_multipliers,
                            point.constraint_multipliers};
      report.objective = objective;
      report.complementarity_residual = residual;
      report.polished = true;
      report.polish_sigma = problem.relaxation();
      report.b_stationary = stationary;
      report.certified = certification.certified;
      report.lpec_value = certification.value;
      report.lpec_radius = certification.radius;
      report.certificate = certification.message;
      return;
    }
    if (outcome.status == Ipopt::User_Requested_Stop) return;  // out of time: keep the homotopy's
  }
}

/// Relaxations at or below this sigma are polished early (phase I of the active-set method).
double earlyPolishSigma(const HomotopyOptions& options) {
  return options.method == MpccMethod::kActiveSet
             ? std::max(options.early_polish_sigma, options.active_set_sigma)
             : options.early_polish_sigma;
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

MpccReport MpccSolver::solveNearSolution(RelaxedMpcc& problem, const std::vector<double>& solution,
                                         double sigma_initial, double wall_time_budget) {
  PrimalDualPoint point;
  point.x = solution;
  point.near_solution = true;
  point.rows_added = true;
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
  } else {
    point.near_solution = true;
  }
  // The previous active set first: one smooth NLP when the problem is (nearly) the same.
  if (options_.polish_active_set && problem.numComplementarities() > 0 &&
      (options_.polish_previous_always ||
       problem.complementarityResidual(point.x.data()) <= options_.polish_rescue_residual)) {
    Stopwatch stopwatch;
    MpccReport report;
    report.solution = point.x;
    report.complementarity_residual = problem.complementarityResidual(point.x.data());
    IpoptSession::SolveSettings settings =
        initialSettings(options_, problem, point.x, wall_time_budget, monitor_);
    settings.warm_start_mu = options_.ipopt.previous_solution_mu;
    settings.warm_start_bound_push = options_.ipopt.previous_solution_bound_push;
    settings.monotone_barrier = true;
    settings.tolerance = options_.ipopt.tolerance;
    settings.max_iterations = options_.previous_polish_iterations > 0
                                  ? options_.previous_polish_iterations
                                  : options_.polish_iterations;
    // The objective the previous solution was polished with: its vanishing terms' weight.
    problem.setVanishingTermsWeight(options_.vanishing_terms_weight);
    problem.setRelaxation(previous.polish_sigma);
    std::vector<double> unsolved;
    polish(*session_, options_, problem, point, options_.complementarity_tolerance, settings,
           options_.polish_attempts, true, monitor_, report, true,
           options_.resume_from_unsolved_polish ? &unsolved : nullptr);
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
    if (!unsolved.empty()) {
      point = PrimalDualPoint{};
      point.x = std::move(unsolved);
      point.near_solution = true;
    }
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
  int consecutive_infeasible = 0, consecutive_failures = 0;
  // Active sets identified by the last converged relaxation and by the last early polishing.
  std::vector<bool> settled_candidate, polished_set;
  bool loosened = false;
  for (int step = 0; step < steps; ++step) {
    problem.setRelaxation(sigma);
    // Following the barrier, the previous NLP ended centred at barrier_factor times its sigma.
    settings.warm_start_mu = options_.barrier_factor > 0.0 && step > 0
                                 ? options_.barrier_factor * sigma / options_.sigma_reduction
                                 : options_.ipopt.warm_start_mu_factor * sigma;
    settings.barrier_target = smooth ? 0.0 : options_.barrier_factor * sigma;
    // A smooth NLP is the whole problem: solved once, at the final tolerance.
    settings.tolerance =
        smooth ? options_.ipopt.tolerance
               : std::max(options_.ipopt.tolerance, options_.relaxed_tolerance_factor * sigma);
    // A cold first relaxation that may start over looser needs no more than its own cap.
    const bool may_loosen = step == 0 && !loosened && !smooth &&
                            options_.loosen_failed_first_relaxation && !start.has_multipliers &&
                            !start.near_solution;
    IpoptSession::SolveSettings step_settings = settings;
    if (may_loosen) {
      const int cap = step_settings.max_iterations > 0 ? step_settings.max_iterations
                                                       : options_.ipopt.max_iterations;
      step_settings.max_iterations = std::min(cap, options_.first_relaxation_iterations);
    }
    const NlpOutcome outcome = session_->solve(problem, point, step_settings);
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
        sigma <= earlyPolishSigma(options_) * (1.0 + 1e-9)) {
      // Polish only an active set that two relaxations in a row identify, once: before it has
      // settled, polishing would fix it, and with it the grid's switch elements, too early.
      problem.setBiactiveRule(options_.polish_biactive_fraction, sigma);
      const std::vector<bool> active_set = problem.identifyActiveSet(point.x.data());
      // Phase I of the active-set method projects every relaxation (the LPEC guards the choice).
      const bool settled =
          options_.method == MpccMethod::kActiveSet || active_set == settled_candidate;
      if (!active_set.empty() && settled && active_set != polished_set) {
        polished_set = active_set;
        IpoptSession::SolveSettings polish_settings = settings;
        polish_settings.tolerance = options_.ipopt.tolerance;
        polish_settings.max_iterations = options_.polish_iterations;
        polish_settings.barrier_target = 0.0;
        if (options_.method == MpccMethod::kActiveSet) {
          problem.setRelaxation(std::min(sigma, options_.branch_nlp_sigma));
        }
        polish(*session_, options_, problem, point, sigma, polish_settings, 1, true, monitor_,
               report);
        problem.setRelaxation(sigma);
        if (polishedToTolerance(report, options_)) {
          report.status = SolveStatus::kSuccess;
          break;
        }
      }
      settled_candidate = active_set;
    }
    report.status = converged ? SolveStatus::kComplementarityNotMet : failureStatus(outcome.status);
    if (interrupted(report.status)) break;
    if (may_loosen && outcome.status == Ipopt::Maximum_Iterations_Exceeded) {
      loosened = true;
      point = start;
      sigma /= options_.sigma_reduction;
      --step;
      continue;
    }
    consecutive_infeasible =
        report.status == SolveStatus::kInfeasible ? consecutive_infeasible + 1 : 0;
    consecutive_failures = converged ? 0 : consecutive_failures + 1;
    if (!converged && (consecutive_infeasible >= options_.max_consecutive_infeasible ||
                       (options_.max_consecutive_failures > 0 &&
                        consecutive_failures >= options_.max_consecutive_failures))) {
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
    settings.barrier_target = 0.0;
    settings.max_iterations = options_.polish_iterations;
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
