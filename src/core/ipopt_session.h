#pragma once

#include <string>
#include <vector>

#include <coin/IpIpoptApplication.hpp>

#include "fesd_trajopt/core/mpcc_solver.h"

namespace fesd {

/// Primal-dual point of an NLP, as Ipopt reports it and takes it for a warm start.
struct PrimalDualPoint {
  std::vector<double> x, bound_lower_multipliers, bound_upper_multipliers, constraint_multipliers;
  bool has_multipliers = false;
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

  /// Solves from `point` and overwrites it with Ipopt's final iterate. When the point has
  /// multipliers it is a warm start with barrier parameter `warm_start_mu`. Stops at
  /// `deadline_seconds` of steady-clock time (<= 0: no deadline).
  NlpOutcome solve(const NlpProblem& problem, PrimalDualPoint& point, double deadline_seconds,
                   double warm_start_mu);

  static std::string statusName(Ipopt::ApplicationReturnStatus status);
  static bool converged(Ipopt::ApplicationReturnStatus status);

 private:
  IpoptSettings settings_;
  Ipopt::SmartPtr<Ipopt::IpoptApplication> application_;
};

/// Seconds on the steady clock, the time base of deadlines.
double steadySeconds();

}  // namespace fesd
