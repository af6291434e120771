#pragma once

#include <limits>
#include <string>
#include <vector>

#include "fesd_trajopt/nlp/nlp_problem.h"

namespace fesd {

/// What one LPEC solve found.
struct LpecResult {
  bool solved = false;      ///< the MILP was solved to optimality
  bool certified = false;   ///< no branch offers linearised descent: B-stationary (MPECopt)
  double value = 0.0;       ///< optimal value: grad f^T d (<= 0; 0 at a B-stationary point)
  double radius = 0.0;      ///< the trust region's radius (infinity norm of d)
  int undecided_pairs = 0;  ///< pairs both of whose sides can vanish within the radius: binaries
  /// A lower bound on the value from the branch NLP's multipliers (-infinity without them);
  /// certified by it alone when it is above the tolerance (no LP solved).
  double dual_bound = -std::numeric_limits<double>::infinity();
  /// The branch of the minimiser, per pair: its left side is the zero one (for fixGivenActiveSet).
  std::vector<bool> left_is_zero;
  bool other_branch = false;  ///< the minimiser leaves the fixed active set
  double seconds = 0.0;
  std::string message;
};

/// How much an LPEC solve may spend beyond the multipliers' bound.
struct LpecBudget {
  bool bound_only = false;  ///< no MILP: certified by the bound or not solved
  /// Branch-and-bound nodes (deterministic, unlike a time limit): on a cluttered scene (9448
  /// variables) a MILP with the default 20000 ran for 51 s.
  int max_nodes = 200;
  double seconds = std::numeric_limits<double>::infinity();  ///< what is left of the solve's budget
};

/// The MPCC linearised at a branch NLP's solution x (MPECopt's LPEC), in the trust region
/// ||d||_inf <= radius:
///   min grad f(x)^T d  s.t.  the rows linearised, the bounds, and for every pair
///   0 <= a(x + d) _|_ b(x + d) >= 0 (the sides are linear, so exactly),
/// solved as a MILP (Cbc; Clp alone when no pair is undecided). Pairs one of whose sides cannot
/// vanish within the radius keep their branch; a binary decides the rest. Optimal value 0
/// certifies B-stationarity; a negative value's branch is the next branch NLP to solve.
/// Built while x's active set is fixed (its data is copied), solvable for several radii.
class Lpec {
 public:
  /// `multipliers`: the branch NLP's constraint multipliers at x (Lagrangian f + lambda^T g), or
  /// empty. With them, solve() first bounds the LPEC's value from below by LP duality (the
  /// reduced costs over the step's box); a bound above the tolerance certifies without an LP.
  /// `relative_tolerance`: a value above -relative_tolerance * radius * max(1, |grad f|_inf)
  /// counts as 0 (the branch NLP is solved only to Ipopt's tolerance).
  Lpec(const RelaxedMpcc& problem, const std::vector<double>& x,
       const std::vector<double>& multipliers, double relative_tolerance);
  LpecResult solve(double radius, const LpecBudget& budget = {}) const;

 private:
  /// The dual bound over the step's box [low, high] (-infinity without multipliers).
  double dualBound(const std::vector<double>& low, const std::vector<double>& high,
                   double radius) const;

  std::vector<double> x_, gradient_, row_lower_, row_upper_, lower_, upper_, released_lower_,
      released_upper_;
  SparsityPattern jacobian_;  ///< of the rows other than the complementarity products
  std::vector<double> jacobian_values_;
  std::vector<FixedPair> pairs_;
  bool has_multipliers_ = false;
  std::vector<double> row_multipliers_;  ///< per kept row
  double tolerance_scale_ = 1.0;
  double relative_tolerance_ = 1e-6;
};

}  // namespace fesd
