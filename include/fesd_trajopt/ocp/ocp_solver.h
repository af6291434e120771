#pragma once

#include <limits>
#include <memory>
#include <string>
#include <vector>

#include "fesd_trajopt/discretization/discretization.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/solver/mpcc_solver.h"

namespace fesd {

/// The discretisation defaults for optimal control: as for simulation, but steps no shorter
/// than h0 / 2. With gamma_h = 1 the optimiser collapsed elements to h = 0 around degenerate
/// (weakly active) switches and so bought grid freedom to exploit discretisation error.
inline DiscretizationOptions optimalControlDiscretization() {
  DiscretizationOptions options;
  options.step_bound = 0.5;
  return options;
}

/// The notes' homotopy (sigma0 = 1, kappa = 0.1, tolerance 1e-9) with Ipopt's free barrier in
/// warm starts and starts next to a plan: over the planning families (node defaults) 16-34 % fewer
/// iterations than the monotone barrier at mu = 1e-6 sigma (docs/results.md, "Hard scenes"). A
/// warm start judges it by the KKT error (Push-T start 10 otherwise crawled 400 iterations in
/// steps of 2e-3), a start next to a plan never returns to a monotone barrier.
inline HomotopyOptions optimalControlHomotopy() {
  HomotopyOptions options;
  options.ipopt.warm_start_barrier = {"adaptive", "kkt-error"};
  options.ipopt.near_solution_barrier = {"adaptive", "never-monotone-mode"};
  return options;
}

struct OcpOptions {
  DiscretizationOptions discretization = optimalControlDiscretization();
  HomotopyOptions homotopy = optimalControlHomotopy();
  /// With FESD, the homotopy first runs on the fixed grid (the standard discretisation: no
  /// cross-complementarity, no step equilibration, h = h0) while sigma > this, then continues
  /// with FESD from that point. The loose relaxations with free steps were the slowest and least
  /// reliable NLPs of all (see README); 0 runs FESD from the start.
  double fixed_grid_until_sigma = 1e-2;
  /// A warm start (solve(previous)) first polishes the previous active set; when that fails, the
  /// homotopy begins at this sigma instead of sigma0, so the previous solution is not relaxed away.
  double warm_start_sigma = 1e-4;
  /// Solving from a TrajectoryGuess (e.g. a planned motion, solve(guess)): the FESD homotopy
  /// starts at this sigma on the guess, without the fixed-grid stage. Measured on the showcase:
  /// the cold start's first relaxed NLP (sigma = 1) wanders 150-500 Ipopt iterations and ends in
  /// a different local optimum under each BLAS; from a planned guess at 1e-2 or 1e-3 the whole
  /// solve agreed to 10 digits under every BLAS, at 0.1 it did not.
  double guess_sigma = 1e-2;
  /// ... and it polishes the active set as soon as two relaxations agree on it
  /// (HomotopyOptions::early_polish_sigma for this solve).
  double guess_early_polish_sigma = 1e-2;
  double activity_tolerance = kDefaultActivityTolerance;
  /// Pass-through depth of an element's polynomial, in state units (see SimulationOptions).
  double penetration_tolerance = kDefaultPenetrationTolerance;
};

/// Where a solve started.
enum class OcpStart {
  kConstant,              ///< every state at x0, controls 0 (solve())
  kGuess,                 ///< a TrajectoryGuess (solve(guess))
  kConstantAfterGuess,    ///< the solve from the guess failed; then from the constant start
  kPrevious,              ///< a previous solution (solve(previous))
  kGuessAfterPrevious,    ///< the warm start failed; then from the guess (solve(previous, guess))
  kTrajectory,            ///< a trajectory on the same grid (solve(trajectory, guess))
  kGuessAfterTrajectory,  ///< that failed; then from the guess
};
/// The start in words; `guess` names what solve(guess) was given (e.g. "push plan"),
/// `trajectory` what solve(trajectory, guess) was.
std::string startName(OcpStart start, const std::string& guess = "guess",
                      const std::string& trajectory = "trajectory");

struct OcpSolution {
  SolveStatus status = SolveStatus::kSolverError;
  OcpStart start = OcpStart::kConstant;
  std::string message;  ///< the solver's, and a warning on unresolved switches
  /// Per element: interval, start time, h, stage states, lambda, c; per interval: u; switches.
  /// Its unresolved_switches (switches inside an element) mark a solution that is not fully
  /// accurate even when the status is kSuccess.
  Trajectory trajectory;
  MpccReport report;  ///< homotopy history, iterations, times, objective, residual
  /// For a solve that started from a TrajectoryGuess: the guess point's residual in the NLP's
  /// equations (NlpAssembly::equalityResidual); NaN otherwise.
  double guess_residual = std::numeric_limits<double>::quiet_NaN();
};

/// Optimal control of a nonsmooth system (any DynamicsModel) with FESD: builds the discretisation
/// once and solves it, from the trivial guess (every state at x0, controls 0 within their bounds)
/// or from a previous solution of the same problem (a warm start).
class OcpSolver {
 public:
  OcpSolver(OcpDefinition ocp, OcpOptions options);

  OcpSolution solve();
  /// Warm start: `previous` must come from a solver with the same discretisation sizes.
  OcpSolution solve(const OcpSolution& previous);
  /// From a guess of the solution, e.g. a planned motion (OcpOptions::guess_sigma). When that
  /// solve fails (neither success nor timeout), solve() follows within what is left of the
  /// wall-time budget; the report then holds both.
  OcpSolution solve(const TrajectoryGuess& guess);
  /// Warm start, and when it fails (neither success nor interrupted) solve(fallback) within what
  /// is left of the budget; the report then holds both. The start names the guess's solve
  /// kGuessAfterPrevious (a further fall back to the constant start stays kConstantAfterGuess).
  OcpSolution solve(const OcpSolution& previous, const TrajectoryGuess& fallback);
  /// From a trajectory on this grid (Discretization::guessFromTrajectory, e.g. the solution of
  /// the same task with fewer contact pairs): the homotopy from OcpOptions::guess_sigma, Ipopt
  /// starting next to it (MpccSolver::solveNearSolution), and when that fails (neither success
  /// nor interrupted) solve(fallback) within what is left of the budget; the report then holds
  /// both.
  OcpSolution solve(const Trajectory& trajectory, const TrajectoryGuess& fallback);
  /// From a plan on this grid that nearly solves this problem (a coarser rung's solution refined
  /// onto it, the round before with fewer pairs or without gap guards): its active set polished
  /// first, i.e. the branch NLP of the plan's contacts, kept if B-stationary; else the homotopy
  /// from the plan at `sigma` (no tighter than warm_start_sigma); and when that fails (neither
  /// success nor interrupted) solve(fallback) within what is left of the budget. `polish_sigma`:
  /// the relaxation whose vanishing terms the plan was polished with (MpccReport::polish_sigma).
  OcpSolution solveFromPlan(const Trajectory& plan, double polish_sigma, double sigma,
                            const TrajectoryGuess& fallback);

  const Discretization& discretization() const { return *discretization_; }
  const OcpOptions& options() const { return options_; }
  /// Watches every later solve (progress, cancel); nullptr: none. Must outlive them.
  void setMonitor(const SolveMonitor* monitor);

 private:
  /// solve() within a wall-time budget (seconds).
  OcpSolution solveFromConstant(double wall_time_budget);
  /// solve(guess) within a wall-time budget (seconds).
  OcpSolution solveFromGuess(const TrajectoryGuess& guess, double wall_time_budget);
  /// The homotopy from a point of the discretisation at guess_sigma, polished early.
  OcpSolution solveFromPoint(const std::vector<double>& point, double wall_time_budget);
  /// `first` when it succeeded or was interrupted; else solve(fallback) within what is left of
  /// the budget, its start `fallback_start` when it began from the guess; `first_name` says
  /// in the message where the first solve began.
  OcpSolution orFallback(OcpSolution first, const TrajectoryGuess& fallback,
                         OcpStart fallback_start, const std::string& first_name);
  /// `later`, started after `earlier` failed: one report with both histories and efforts.
  static OcpSolution after(const OcpSolution& earlier, OcpSolution later);
  /// The solution read from `report`, whose point belongs to `source`.
  OcpSolution finish(MpccReport report, const Discretization& source) const;

  OcpDefinition ocp_;
  OcpOptions options_;
  std::unique_ptr<Discretization> discretization_;
  std::unique_ptr<Discretization> fixed_grid_;  ///< the standard method on the same grid
  MpccSolver solver_, fixed_grid_solver_, guess_solver_, plan_solver_;
};

/// The OCP's system from its initial state under the given controls (one per control interval)
/// with the FESD integrator, one step per control interval, on the given discretisation.
SimulationResult resimulate(const OcpDefinition& ocp, const std::vector<Eigen::VectorXd>& controls,
                            const SimulationOptions& fine);

/// Re-simulates a solution's controls with the FESD integrator (one step per control interval,
/// the given, typically finer, discretisation) and returns the distance between the simulated
/// terminal state and the OCP's; infinity when the simulation fails.
double resimulationError(const OcpDefinition& ocp, const OcpSolution& solution,
                         const SimulationOptions& fine);

}  // namespace fesd
