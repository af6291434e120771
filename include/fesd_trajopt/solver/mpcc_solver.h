#pragma once

#include <atomic>
#include <functional>
#include <limits>
#include <map>
#include <memory>
#include <string>
#include <vector>

#include "fesd_trajopt/nlp/nlp_problem.h"

namespace fesd {

/// The name of our own sparse LDL^T as IpoptSettings::linear_solver.
inline const char* const kLdltSolver = "ldlt";

/// Ipopt's barrier in one kind of start: its mu_strategy and, for "adaptive", how Ipopt judges the
/// free barrier's progress (its adaptive_mu_globalization).
struct BarrierStrategy {
  std::string mu_strategy = "monotone";
  std::string globalization = "obj-constr-filter";
};

/// Options passed to Ipopt for every relaxed NLP.
struct IpoptSettings {
  double tolerance = 1e-10;
  double acceptable_tolerance = 1e-8;
  int max_iterations = 500;  ///< per relaxed NLP
  int print_level = 0;
  /// The barrier of a warm start (the previous relaxation's solution and multipliers) and of a
  /// start next to a plan's point. "monotone" suits a simulation's homotopy (Example 1:
  /// "adaptive" took 1.5-2.2x the iterations); optimal control frees the barrier
  /// (optimalControlHomotopy): there a tighter relaxation moves contacts, and a barrier fixed at
  /// 1e-6 sigma crept to them in steps of 10-20 %.
  BarrierStrategy warm_start_barrier;
  BarrierStrategy near_solution_barrier;
  /// Barrier strategy of a cold start (the first relaxed NLP): "adaptive" needed about 40 %
  /// fewer iterations on the manipulation OCP. Its globalization is Ipopt's (or extra_options').
  std::string cold_start_mu_strategy = "adaptive";
  /// kLdltSolver (ours: multifrontal LDL^T, state per solve, solves in parallel threads) or
  /// "mumps" (Debian's Ipopt's own; one solve per process at a time).
  std::string linear_solver = kLdltSolver;
  /// A warm-started homotopy step starts at the previous solution with its multipliers, pushed
  /// off the bounds by only this much, and with Ipopt's mu_init = warm_start_mu_factor * sigma:
  /// a barrier parameter consistent with that point, so Ipopt does not re-centre far away.
  double warm_start_mu_factor = 1e-6;
  double warm_start_bound_push = 1e-9;
  /// Ipopt's mu_init and bound push when polishing a previous solution's active set
  /// (MpccSolver::solve(previous)). The previous solution of a changed task (the showcase's
  /// object target moved by 0.3: objective 90 at the old optimum against 0.056) is far from the
  /// new optimum, and Ipopt needs room to move: with the homotopy's setting (mu = 1e-10, push
  /// 1e-9) it took 47 iterations; with mu = 1e-11 (below the tolerance 1e-10, so no barrier
  /// reduction at the end) and push 1e-3, 15 (target moved by -0.3: 19 -> 15; the same task
  /// again: 11 -> 13). mu_init = 1e-7 cost more in every case.
  double previous_solution_mu = 1e-11;
  double previous_solution_bound_push = 1e-3;
  /// Ipopt's mu_init and bound push (bound multipliers mu_init / slack) from a plan's primal point
  /// alone (a graze round's, a lazy round's, a finer rung's): Ipopt's cold start re-centred it to
  /// mu = 0.1 and walked back in 70-170 iterations (docs/results.md).
  double near_solution_mu = 1e-9;
  double near_solution_bound_push = 1e-6;
  /// ... when the point violates the NLP's bounds and rows by at most this (< 0: never); a point
  /// farther off (a plan through the pairs a lazy round adds, a plan mapped to more stages) is
  /// started cold: at mu_init 1e-9 Ipopt crept back to feasibility.
  double near_solution_violation = 1e-3;
  /// The largest barrier parameter of a cold start from a plan solved without some of the NLP's
  /// rows (a lazy round's: the plan passes through the pairs it adds); 0: Ipopt's own bound. Its
  /// adaptive barrier otherwise rose to mu = 3e3 there, the objective from 9e-3 to 3.5e3, and took
  /// 212 iterations to come back (posts seed 7); capped at 0.1, the posts family's seeds 0-7 took
  /// 789 iterations instead of 959 (docs/results.md).
  double added_rows_mu_max = 0.1;
  /// Any further Ipopt option by name; the value's type (integer, number, text) is inferred.
  std::map<std::string, std::string> extra_options;
};

/// How the MPCC is solved after its relaxations have found an active set.
enum class MpccMethod {
  /// The homotopy to the complementarity tolerance, its active set polished at the end (or
  /// early), B-stationarity judged by the polished point's multipliers.
  kHomotopy,
  /// After MPECopt (Nurkanovic & Leyffer 2025): relaxed NLPs only until an active set's branch
  /// NLP (BNLP) solves (phase I), then at each BNLP solution an LPEC in a trust region that
  /// certifies B-stationarity or gives the next branch (phase II).
  kActiveSet,
};
std::string methodName(MpccMethod method);
/// "homotopy" or "active_set"; false for another name.
bool parseMethod(const std::string& name, MpccMethod& method);

/// The Scholtes homotopy: solve the NLP with 0 <= a, 0 <= b, a*b <= sigma for
/// sigma = sigma0, kappa*sigma0, ... until the complementarity residual is below tolerance.
struct HomotopyOptions {
  double sigma_initial = 1.0;
  double sigma_reduction = 0.1;  ///< kappa
  double complementarity_tolerance = 1e-9;
  int max_steps = 30;
  /// The homotopy stops before sigma falls below this: tighter relaxations are as hard for
  /// Ipopt (tolerance 1e-10) as the MPCC itself, so further steps cannot help.
  double minimum_sigma = 1e-13;
  /// Weight of the objective terms that vanish with sigma (FESD's step regulariser); 0 drops
  /// them. A different weight gives the homotopy a different path.
  double vanishing_terms_weight = 1.0;
  /// Inexact homotopy: a relaxed NLP is solved to Ipopt tolerance
  /// max(ipopt.tolerance, relaxed_tolerance_factor * sigma); loose relaxations only guide.
  double relaxed_tolerance_factor = 1e-2;
  /// A homotopy that follows the barrier: > 0 ends each relaxed NLP on the central path at
  /// Ipopt's mu = barrier_factor * sigma (mu_target) and starts the next one there (mu_init);
  /// 0 solves each to its tolerance and starts the next at warm_start_mu_factor * sigma.
  double barrier_factor = 0.0;
  /// Objective scaling: > 0 is Ipopt's obj_scaling_factor; 0 (default) scales so that the
  /// objective at the initial guess is at most objective_scale_target in size.
  double objective_scaling = 0.0;
  double objective_scale_target = 1e3;
  /// A relaxed NLP that ends without converging does not abort the homotopy: the next, tighter
  /// one starts from its iterate (as the reference implementation does), until this many in a
  /// row have failed (0: no limit; 1: the first failure ends the homotopy). A limit is for
  /// homotopies with a fallback behind them (a plan's verification: retry, twice the elements,
  /// fixed steps), where a run of failures to the end costs more than the fallback.
  int max_consecutive_failures = 0;
  /// ... and after this many relaxed NLPs in a row that Ipopt found locally infeasible.
  /// Measured (bench homotopy-failures and single runs): homotopies recovered after runs of up
  /// to 7 other failures (iteration limit on the aligned-chain OCP, restoration failures in a
  /// showcase re-simulation step), never after an infeasible one; on an infeasible simulation
  /// step every relaxation failed (14 in a row, 3-8 times the time of stopping, same status).
  int max_consecutive_infeasible = 3;
  /// A first relaxed NLP started cold that runs to Ipopt's iteration limit is too tight for its
  /// start: the homotopy starts again from that start, once, at sigma / kappa (an OCP's solve
  /// from its first guess: OcpSolver; a simulation step splits instead).
  bool loosen_failed_first_relaxation = false;
  /// ... and that first relaxation stops after this many Ipopt iterations (the others at
  /// ipopt.max_iterations): of about 100 planning scenes, first relaxations converged within 173
  /// or ran to Ipopt's 500 (cluttered seeds 19, 106, 110), and those start over the same either
  /// way.
  int first_relaxation_iterations = 200;
  double wall_time_budget = std::numeric_limits<double>::infinity();  ///< seconds, per solve
  /// After the homotopy converges, fix the identified active set and solve the resulting smooth
  /// NLP once more (RelaxedMpcc::fixActiveSet): complementarity then holds exactly instead of
  /// to O(sigma), which removes the sigma-blur of switch times (release times are only pinned
  /// to O(sigma / h^2) by a relaxed pair, because c leaves the boundary quadratically) and makes
  /// equilibrated steps exactly equal. If the polished NLP fails, the most ambiguous pairs are
  /// flipped one at a time (up to polish_attempts solves); if all fail, the homotopy's point
  /// is kept.
  bool polish_active_set = true;
  int polish_attempts = 3;
  /// Biactive pairs in polishing (RelaxedMpcc::setBiactiveRule): a pair whose two sides are both
  /// below this fraction of the relaxation's scale sqrt(sigma) (in the pair's weighted units) is
  /// left to the polished NLP with both sides >= 0 and no product row, instead of having its
  /// (arbitrary) smaller side fixed. Fixing one side of a pair whose other side the remaining
  /// equations hold at zero (a body resting against another without force: its c stays 0 while
  /// nothing moves) leaves Ipopt a feasible set without interior (56-65 iterations of restoration
  /// and tiny steps instead of 11 on the showcase with a disc in the way) and multipliers that
  /// make the point look non-B-stationary (the fixed side's d Lagrangian is an artefact of the
  /// barrier, 13-2543 there) although it is a minimiser of the relaxed NLP. 0: every pair gets
  /// a fixed side.
  double polish_biactive_fraction = 0.1;
  /// Early exit: once two converged relaxed NLPs in a row with sigma <= this identify the same
  /// active set, it is polished (once); a polished point that meets the complementarity
  /// tolerance and is B-stationary (RelaxedMpcc::biactiveDescent <= stationarity_tolerance) ends
  /// the homotopy. The tighter relaxations after it would only re-derive the same active set.
  /// 0 (default) polishes only after the homotopy has converged: on the test suite's Filippov
  /// OCP (56) and a tiny-scale simulation, early polishing settled on other (worse) switch
  /// placements than the full homotopy.
  double early_polish_sigma = 0.0;
  /// Largest descent (relative to the objective's gradient) that a biactive pair's fixed side
  /// may offer at an accepted early or warm-start polished point.
  double stationarity_tolerance = 1e-6;
  /// When an early or warm-start polished point fails that test, the other branch is checked:
  /// the pairs it left biactive flipped (their free side fixed, the fixed one freed) and solved
  /// from the point within this many Ipopt iterations (0: no check). If that branch offers no
  /// lower objective (relative 1e-8) either, the point counts as B-stationary on both branches.
  /// The multiplier test is only sufficient: where a biactive pair's free side is held at zero
  /// by the other rows (a body left resting against another without force, whose force would
  /// push them apart), the multipliers are not unique and no choice may have the test's signs
  /// although every branch keeps the point (the showcase with a disc at (0.5, 6): the flipped
  /// branch returned the same objective in 10 iterations, 213 -> 61 in all).
  int branch_check_iterations = 30;
  /// An early or warm-start polished point whose branch check did not solve within its
  /// iterations is kept (b_stationary false: nothing shown either way) instead of the homotopy
  /// going on. On cluttered seed 22's replans the homotopy then went on to sigma 1e-10 (130-190
  /// iterations there) from points that Cbc's LPEC certified B-stationary every time.
  bool accept_unsolved_branch_check = false;
  /// Ipopt iterations for polishing an active set (early polishing, a previous solution's or a
  /// plan's, the last relaxation's): near its solution a branch NLP converges in tens of
  /// iterations (warm replans 11-15, a plan refined onto a finer grid 15-40); one whose active
  /// set does not fit ran to Ipopt's limit of 500 (a lazy round's new pair the plan passed
  /// through; an early polish of a push along a wall; cluttered seed 114's last relaxations,
  /// three attempts each time, until its budget ran out).
  int polish_iterations = 100;
  /// A homotopy that fails later still gets a polishing attempt from its best converged
  /// relaxed NLP, if that one's complementarity residual is at most this: polishing needs the
  /// right active set, not a tiny sigma.
  double polish_rescue_residual = 1e-4;
  /// From a previous solution: its active set is polished first when the start's residual is
  /// at most polish_rescue_residual, or always. A plan mapped onto a finer grid is a solution
  /// whose new stage points, interpolated, leave products up to 2.6 that fixing its active set
  /// removes (the Panda's 4 cm puck's last rung: 534 -> 42 Ipopt iterations).
  bool polish_previous_always = false;
  /// Ipopt iterations for that polish of a previous solution's or a plan's active set (0:
  /// polish_iterations). A replan from the plant's state starts off its plan, and a polish
  /// that had not converged by 50 iterations did not by 100 (planning/scene_solver.cpp).
  int previous_polish_iterations = 0;
  /// When that polish does not solve, the homotopy resumes from its last iterate instead of from
  /// the previous solution, if the iterate meets its branch NLP's rows and bounds to
  /// ipopt.near_solution_violation. A replan's polish moves the plan onto the plant's state with
  /// its old contacts before it stalls (cluttered seed 22: feasible to 1e-9 and its objective
  /// settled after ~10 of its 50 iterations), and from there the relaxation at 1e-4 took 23-50
  /// Ipopt iterations instead of 45-64. Graze rounds of a first plan did not gain (seed 7: 1840
  /// -> 2182 iterations), so it is for replans.
  bool resume_from_unsolved_polish = false;
  /// A warm start whose point meets the KKT conditions of the previous active set's branch NLP
  /// to this (primal, bound complementarity; dual relative to max(1, |grad f|_inf)) is accepted
  /// without an Ipopt iteration: an unchanged request answers with its previous solution.
  double solved_start_tolerance = 1e-8;
  MpccMethod method = MpccMethod::kHomotopy;
  /// Active-set method: a converged relaxation at sigma <= this is projected onto its active set
  /// and that branch NLP solved (phase I ends when one solves and its LPEC certifies it).
  double active_set_sigma = 1e-2;
  /// ... and its branch NLP keeps the vanishing terms (FESD's step regulariser) and relaxed rows
  /// of this relaxation, or of the projected one if smaller: the weight the homotopy's own
  /// polishing has where its active set settles (sigma = 1e-3 on the showcase), so that both
  /// methods end on the same objective when they find the same branch.
  double branch_nlp_sigma = 1e-3;
  /// The LPEC's trust region (infinity norm of the step, in the NLP's variables: MPECopt's 1e-3);
  /// halved after a branch it proposes brings no decrease, at most lpec_radius_halvings times.
  double lpec_radius = 1e-3;
  int lpec_radius_halvings = 3;
  /// Branch NLPs phase II may solve after the first one of a polishing stage.
  int max_branch_changes = 5;
  /// An LPEC value above -lpec_tolerance * radius * max(1, |grad f|_inf) counts as zero: the
  /// multipliers' bound sums the branch NLP's dual residuals over all variables (-1.6e-6 per
  /// unit radius on the showcase, solved to Ipopt's 1e-10); a branch that offers real descent
  /// offers a contact force's worth.
  double lpec_tolerance = 1e-4;
  IpoptSettings ipopt;
};

enum class SolveStatus {
  kSuccess,                ///< converged with the complementarity residual below tolerance
  kMaxIterations,          ///< Ipopt hit its iteration limit in the last relaxed NLP
  kInfeasible,             ///< Ipopt found the relaxed NLP locally infeasible
  kTimeout,                ///< the wall-time budget ran out; the best iterate is returned
  kComplementarityNotMet,  ///< the homotopy ended above the complementarity tolerance
  kSolverError,            ///< Ipopt failed otherwise (restoration failure, bad values, ...)
  kCancelled,              ///< SolveMonitor::cancel was set; the best iterate is returned
  kAccuracyNotMet,         ///< an accuracy target was not met on any rung (the scene layer's)
  /// Solved, but a body (or joint) ends farther from its target than the target tolerance (the
  /// scene layer's): the best plan found, not what was asked for.
  kTargetNotReached,
};
std::string statusName(SolveStatus status);
/// The solve was stopped from outside (timeout or cancel): keep the best iterate, try nothing more.
inline bool interrupted(SolveStatus status) {
  return status == SolveStatus::kTimeout || status == SolveStatus::kCancelled;
}

/// One relaxed NLP of the homotopy.
struct HomotopyStep {
  double sigma;  ///< 0 marks the polishing solve
  int iterations;
  double complementarity_residual;
  double objective;
  std::string ipopt_status;
  double wall_seconds;
  bool converged;  ///< Ipopt solved this NLP (to tolerance or to the acceptable level)
};

/// Watches a running solve from another thread's point of view: told after every relaxed (or
/// polishing) NLP, and asked between Ipopt iterations whether to stop.
struct SolveMonitor {
  std::function<void(const HomotopyStep&)> on_step;
  /// Set to stop the solve at the next Ipopt iteration: it ends kCancelled with the best iterate.
  const std::atomic<bool>* cancel = nullptr;
  bool cancelled() const { return cancel != nullptr && cancel->load(); }
};

/// Multipliers of an NLP solution (bounds and constraints), for warm starts.
struct NlpMultipliers {
  std::vector<double> bound_lower, bound_upper, constraints;
  bool empty() const { return constraints.empty() && bound_lower.empty(); }
};

struct MpccReport {
  SolveStatus status = SolveStatus::kSolverError;
  std::string message;
  std::vector<HomotopyStep> history;
  /// The last accepted iterate; after a timeout the best one: the converged relaxed NLP with
  /// the smallest residual, else the start or the interrupted NLP's last iterate, whichever
  /// violates the constraints less.
  std::vector<double> solution;
  NlpMultipliers multipliers;  ///< its multipliers
  double objective = 0.0;
  double complementarity_residual = 0.0;
  int iterations = 0;     ///< Ipopt iterations over all homotopy steps
  bool polished = false;  ///< the solution comes from the active-set polishing solve
  /// The relaxation the polished NLP was solved at: its vanishing terms (FESD's step regulariser)
  /// kept that weight, and so does a warm start's polish from this solution. Without them the
  /// showcase warm-started from its own optimum moved to a plan 0.1 % cheaper whose verification
  /// error was 7x larger (1.3e-2 against 1.9e-3): element lengths its steps had kept even.
  double polish_sigma = 0.0;
  /// A polished solution is B-stationary: no biactive pair offers descent (always true for
  /// early and warm-start polishing, which require it).
  bool b_stationary = false;
  /// The active-set method's certificate: the last LPEC at the solution found no descent on any
  /// branch within its radius (b_stationary then holds too).
  bool certified = false;
  /// The last LPEC's optimal value (0 when certified; NaN when none ran).
  double lpec_value = std::numeric_limits<double>::quiet_NaN();
  double lpec_radius = 0.0;  ///< its trust region's radius
  std::string certificate;   ///< the last LPEC in words ("" if none ran)
  int branch_nlps = 0;       ///< branch NLPs solved (polishing solves and phase II's)
  int lpecs = 0;             ///< LPECs solved
  double lpec_seconds = 0.0;
  double wall_seconds = 0.0, cpu_seconds = 0.0;
  double ipopt_seconds = 0.0;  ///< wall time inside Ipopt itself (solve time minus evaluations)
  double evaluation_seconds = 0.0;  ///< wall time inside our function evaluations

  bool converged() const { return status == SolveStatus::kSuccess; }
  int failedSteps() const;  ///< relaxed (or polishing) NLPs that Ipopt did not solve
  int relaxedNlps() const;  ///< relaxed NLPs in the history (sigma > 0)
  void addEffort(const MpccReport& other);   ///< adds another solve's iterations and times
  void accumulate(const MpccReport& other);  ///< addEffort, and the worse residual
};

/// One line: status, homotopy steps, iterations, last NLP, residual, polishing.
std::string describe(const MpccReport& report, double tolerance);

class IpoptSession;
struct PrimalDualPoint;

/// Solves a RelaxedMpcc by the homotopy, each NLP by Ipopt with exact sparse derivatives,
/// warm-started from the previous one. A solver keeps one Ipopt application and can be reused
/// for many problems; it is not thread-safe (use one per thread). Solvers in different threads
/// solve in parallel with our LDL^T; with MUMPS (not thread-safe) their solves take turns.
class MpccSolver {
 public:
  explicit MpccSolver(HomotopyOptions options = {});
  ~MpccSolver();
  MpccSolver(const MpccSolver&) = delete;
  MpccSolver& operator=(const MpccSolver&) = delete;

  const HomotopyOptions& options() const { return options_; }
  /// Watches every later solve (nullptr: none); the monitor must outlive them.
  void setMonitor(const SolveMonitor* monitor) { monitor_ = monitor; }
  /// Solves from the initial guess, the homotopy starting at `sigma_initial` (default: the
  /// options'). With zero complementarity constraints the problem is a smooth NLP and is solved
  /// once, without homotopy.
  /// `wall_time_budget` (seconds, if >= 0) replaces the options' budget for this call.
  MpccReport solve(RelaxedMpcc& problem, const std::vector<double>& initial_guess,
                   double sigma_initial = -1.0, double wall_time_budget = -1.0);
  /// As solve(initial_guess), from a solution of a nearby problem without its multipliers (a plan
  /// with pairs added): Ipopt starts next to it (IpoptSettings::near_solution_*), or cold with
  /// its barrier parameter bounded when the point is farther (IpoptSettings::added_rows_mu_max).
  MpccReport solveNearSolution(RelaxedMpcc& problem, const std::vector<double>& solution,
                               double sigma_initial, double wall_time_budget);
  /// A warm start from a previous solution of the same problem, multipliers included: its
  /// active set polished first (IpoptSettings::previous_solution_*), then, if that fails, the
  /// homotopy from sigma_initial. Without its multipliers (a plan's point) Ipopt starts next to
  /// it instead (IpoptSettings::near_solution_*).
  MpccReport solve(RelaxedMpcc& problem, const MpccReport& previous, double sigma_initial,
                   double wall_time_budget = -1.0);

 private:
  MpccReport run(RelaxedMpcc& problem, PrimalDualPoint point, double sigma_initial,
                 double wall_time_budget);

  HomotopyOptions options_;
  std::unique_ptr<IpoptSession> session_;
  const SolveMonitor* monitor_ = nullptr;
};

}  // namespace fesd
