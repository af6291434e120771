#pragma once

#include <map>
#include <string>
#include <vector>

#include <coin/IpIpoptApplication.hpp>

#include "fesd_trajopt/solver/mpcc_solver.h"

namespace fesd {

/// Primal-dual point of an NLP, as Ipopt reports it and takes it for a warm start.
struct PrimalDualPoint {
  std::vector<double> x, bound_lower_multipliers, bound_upper_multipliers, constraint_multipliers;
  bool has_multipliers = false;
  /// Without multipliers: x solves a nearby NLP (the same plan with more rows, or re-gridded);
  /// Ipopt starts next to it (IpoptSettings::near_solution_*) when it is that near this one.
  bool near_solution = false;
  /// x solves this NLP without some of its rows (a lazy round's plan through its new pairs): a
  /// cold start from it bounds the barrier parameter (IpoptSettings::added_rows_mu_max).
  bool rows_added = false;
};

/// What one Ipopt solve produced.
struct NlpOutcome {
  Ipopt::ApplicationReturnStatus status;
  int iterations = 0;
  double objective = 0.0;
  double wall_seconds = 0.0;
  double evaluation_seconds = 0.0;
};

/// One Ipopt application with fixed options, solving NlpProblems from a given primal-dual point.
class IpoptSession {
 public:
  explicit IpoptSession(const IpoptSettings& settings);
  ~IpoptSession();
  IpoptSession(const IpoptSession&) = delete;
  IpoptSession& operator=(const IpoptSession&) = delete;

  /// What may change from one solve to the next.
  struct SolveSettings {
    double deadline_seconds = 0.0;  ///< steady-clock time to stop at; <= 0: none
    double warm_start_mu = 1e-4;    ///< barrier parameter of a warm start
    double tolerance = 1e-10;
    double objective_scaling = 1.0;
    const std::atomic<bool>* cancel = nullptr;  ///< set: stop at the next iteration
    double warm_start_bound_push = 0.0;         ///< > 0: replaces the session's for this solve
    int max_iterations = 0;                     ///< > 0: replaces the session's for this solve
    /// Ipopt's mu_target: > 0 ends the solve on the central path at this barrier parameter.
    double barrier_target = 0.0;
    /// A warm start on Ipopt's monotone barrier from warm_start_mu, whatever the session's
    /// warm_start_barrier (a previous solution's start below the tolerance must not re-centre).
    bool monotone_barrier = false;
  };
  /// Solves from `point` and overwrites it with Ipopt's final iterate; a point with multipliers
  /// is a warm start.
  NlpOutcome solve(const NlpProblem& problem, PrimalDualPoint& point,
                   const SolveSettings& settings);

  static std::string statusName(Ipopt::ApplicationReturnStatus status);
  static bool converged(Ipopt::ApplicationReturnStatus status);

 private:
  IpoptSettings settings_;
  bool uses_mumps_;
  /// Ipopt's starting options of a cold start (its defaults, or the user's extra_options),
  /// restored after a start next to a solution changed them.
  std::map<std::string, std::string> cold_start_options_;
  /// An application configured from settings_, its barrier parameter bounded by mu_max (0:
  /// Ipopt's own bound, from the starting point: once set, Ipopt's option cannot be unset).
  Ipopt::SmartPtr<Ipopt::IpoptApplication> newApplication(double mu_max);
  Ipopt::SmartPtr<Ipopt::IpoptApplication> application_;
  Ipopt::SmartPtr<Ipopt::IpoptApplication> bounded_barrier_application_;  ///< made when first used
};

/// Seconds on the steady clock, the time base of deadlines.
double steadySeconds();

}  // namespace fesd
