#include "fesd_trajopt/solver/lpec.h"

#include <coin/CbcModel.hpp>
#include <coin/CoinPackedMatrix.hpp>
#include <coin/OsiClpSolverInterface.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <mutex>
#include <sstream>

#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {

namespace {

/// NlpProblem's bounds at or beyond this are infinite.
constexpr double kInfiniteBound = 1e19;
/// A zero side's value at x of at most this counts as zero (data fixed near zero, rounding).
constexpr double kZeroSide = 1e-9;

/// The range of side^T d over the box [lower, upper].
std::pair<double, double> range(const LinearExpression& side, const std::vector<double>& lower,
                                const std::vector<double>& upper) {
  double low = 0.0, high = 0.0;
  for (const LinearTerm& t : side) {
    const double a = t.coefficient * lower[t.variable], b = t.coefficient * upper[t.variable];
    low += std::min(a, b);
    high += std::max(a, b);
  }
  return {low, high};
}

/// The LP's rows as triplets with their bounds.
struct LpRows {
  std::vector<int> rows, cols;
  std::vector<double> values, lower, upper;
  int count = 0;
  int add(double low, double high) {
    lower.push_back(low);
    upper.push_back(high);
    return count++;
  }
  void addTerms(int row, const LinearExpression& side) {
    for (const LinearTerm& t : side) entry(row, t.variable, t.coefficient);
  }
  void entry(int row, int col, double value) {
    rows.push_back(row);
    cols.push_back(col);
    values.push_back(value);
  }
};

/// Solves min cost^T v over the rows and column bounds, columns from `first_binary` on binary,
/// by Cbc over Clp; false unless proven optimal.
bool solveMilp(const LpRows& lp, const std::vector<double>& lower, const std::vector<double>& upper,
               const std::vector<double>& cost, int first_binary, const LpecBudget& budget,
               double& value, std::vector<double>& solution) {
  const int columns = static_cast<int>(cost.size());
  CoinPackedMatrix matrix(false, lp.rows.data(), lp.cols.data(), lp.values.data(),
                          static_cast<CoinBigIndex>(lp.values.size()));
  // Trailing columns in no row (variables only the objective or the bounds see) count too.
  matrix.setDimensions(lp.count, columns);
  // Requests are solved in parallel threads; Clp's and Cbc's thread safety across models is not
  // documented, and the MILP is rare (the dual bound certifies first), so one runs at a time.
  static std::mutex milp_mutex;
  const std::lock_guard<std::mutex> lock(milp_mutex);
  OsiClpSolverInterface lp_solver;
  lp_solver.messageHandler()->setLogLevel(0);
  lp_solver.loadProblem(matrix, lower.data(), upper.data(), cost.data(), lp.lower.data(),
                        lp.upper.data());
  for (int b = first_binary; b < columns; ++b) lp_solver.setInteger(b);
  CbcModel model(lp_solver);
  model.setLogLevel(0);
  model.messageHandler()->setLogLevel(0);
  model.solver()->messageHandler()->setLogLevel(0);
  model.setMaximumNodes(budget.max_nodes);
  model.setNumberStrong(0);  // each strong-branching trial is an LP of the NLP's size
  if (std::isfinite(budget.seconds)) model.setMaximumSeconds(std::max(budget.seconds, 1e-3));
  model.setAllowableGap(0.0);
  model.setAllowableFractionGap(0.0);
  model.branchAndBound();
  if (!model.isProvenOptimal() || model.bestSolution() == nullptr) return false;
  value = model.getObjValue();
  solution.assign(model.bestSolution(), model.bestSolution() + columns);
  return true;
}

}  // namespace

Lpec::Lpec(const RelaxedMpcc& problem, const std::vector<double>& x,
           const std::vector<double>& multipliers, double relative_tolerance)
    : x_(x), relative_tolerance_(relative_tolerance) {
  has_multipliers_ = static_cast<int>(multipliers.size()) == problem.numConstraints();
  const int n = problem.numVariables(), m = problem.numConstraints();
  gradient_.resize(n);
  problem.objectiveGradient(x.data(), gradient_.data());
  for (double g : gradient_) tolerance_scale_ = std::max(tolerance_scale_, std::fabs(g));
  std::vector<double> g_lower(m), g_upper(m), g(m);
  lower_.resize(n);
  upper_.resize(n);
  problem.getBounds(lower_.data(), upper_.data(), g_lower.data(), g_upper.data());
  released_lower_.resize(n);
  released_upper_.resize(n);
  problem.boundsBeforeActiveSet(released_lower_.data(), released_upper_.data());
  problem.constraints(x.data(), g.data());
  pairs_ = problem.fixedPairs();
  // The product rows are replaced by the pairs' disjunctions; rows without bounds say nothing.
  std::vector<bool> product(m, false);
  for (int row : problem.complementarityRows()) product[row] = true;
  std::vector<int> row_of(m, -1);  // the LP row of each constraint row kept (-1: dropped)
  for (int i = 0; i < m; ++i) {
    const bool bounded = g_lower[i] > -kInfiniteBound || g_upper[i] < kInfiniteBound;
    if (product[i] || !bounded) continue;
    row_of[i] = static_cast<int>(row_lower_.size());
    if (has_multipliers_) row_multipliers_.push_back(multipliers[i]);
    // d = 0 stays feasible where x meets a row only to Ipopt's tolerance.
    row_lower_.push_back(g_lower[i] > -kInfiniteBound ? std::min(g_lower[i] - g[i], 0.0)
                                                      : -COIN_DBL_MAX);
    row_upper_.push_back(g_upper[i] < kInfiniteBound ? std::max(g_upper[i] - g[i], 0.0)
                                                     : COIN_DBL_MAX);
  }
  const SparsityPattern& pattern = problem.jacobianPattern();
  std::vector<double> values(pattern.nonzeros());
  problem.jacobian(x.data(), values.data());
  for (int e = 0; e < pattern.nonzeros(); ++e) {
    if (row_of[pattern.rows[e]] < 0 || values[e] == 0.0) continue;
    jacobian_.add(row_of[pattern.rows[e]], pattern.cols[e]);
    jacobian_values_.push_back(values[e]);
  }
}

double Lpec::dualBound(const std::vector<double>& low, const std::vector<double>& high,
                       double radius) const {
  if (!has_multipliers_) return -std::numeric_limits<double>::infinity();
  // grad f^T d = r^T d - lambda^T J d with the reduced costs r = grad f + J^T lambda; each term
  // bounded over the box, each row's J d over its bounds and what the trust region lets it reach.
  const int kept_rows = static_cast<int>(row_lower_.size());
  std::vector<double> reduced = gradient_, reach(kept_rows, 0.0);
  for (int e = 0; e < jacobian_.nonzeros(); ++e) {
    reduced[jacobian_.cols[e]] += row_multipliers_[jacobian_.rows[e]] * jacobian_values_[e];
    reach[jacobian_.rows[e]] += radius * std::fabs(jacobian_values_[e]);
  }
  double bound = 0.0;
  for (size_t j = 0; j < reduced.size(); ++j) {
    bound += std::min(reduced[j] * low[j], reduced[j] * high[j]);
  }
  for (int i = 0; i < kept_rows; ++i) {
    const double lower = std::max(row_lower_[i], -reach[i]),
                 upper = std::min(row_upper_[i], reach[i]);
    bound += std::min(-row_multipliers_[i] * lower, -row_multipliers_[i] * upper);
  }
  return bound;
}

LpecResult Lpec::solve(double radius, const LpecBudget& budget) const {
  Stopwatch stopwatch;
  LpecResult result;
  result.radius = radius;
  const int n = static_cast<int>(x_.size());
  // The step's box: the bounds of the fixed branch and the trust region, d = 0 inside.
  const auto box = [&](const std::vector<double>& lower, const std::vector<double>& upper, int j,
                       double& low, double& high) {
    low = lower[j] <= -kInfiniteBound ? -radius : std::max(lower[j] - x_[j], -radius);
    high = upper[j] >= kInfiniteBound ? radius : std::min(upper[j] - x_[j], radius);
    low = std::min(low, 0.0);
    high = std::max(high, 0.0);
  };
  std::vector<double> low(n), high(n);
  for (int j = 0; j < n; ++j) box(lower_, upper_, j, low[j], high[j]);
  // Undecided pairs: the other side can vanish too within the radius (or both are free).
  const int pairs = static_cast<int>(pairs_.size());
  std::vector<bool> undecided(pairs, false);
  std::vector<bool> released(n, false);
  for (int p = 0; p < pairs; ++p) {
    const FixedPair& pair = pairs_[p];
    const double other = linearValue(pair.other_side, x_.data());
    if (pair.biactive || other + range(pair.other_side, low, high).first <= kZeroSide) {
      undecided[p] = true;
      for (const LinearTerm& t : pair.zero_side) released[t.variable] = true;
    }
  }
  result.left_is_zero.resize(pairs);
  for (int p = 0; p < pairs; ++p) result.left_is_zero[p] = pairs_[p].zero_side_is_left;
  for (int j = 0; j < n; ++j) {
    if (released[j]) box(released_lower_, released_upper_, j, low[j], high[j]);
  }
  const double tolerance = relative_tolerance_ * radius * tolerance_scale_;
  result.dual_bound = dualBound(low, high, radius);
  if (result.dual_bound >= -tolerance) {
    // Every step in the box, on any branch, costs at least the bound: nothing to search.
    result.solved = result.certified = true;
    std::ostringstream message;
    message << "B-stationary within radius " << radius << " by the multipliers' bound "
            << result.dual_bound << " (" << std::count(undecided.begin(), undecided.end(), true)
            << " pairs near a switch)";
    result.message = message.str();
    result.seconds = stopwatch.wallSeconds();
    return result;
  }
  if (budget.bound_only || budget.seconds <= 0.0) {
    std::ostringstream message;
    message << "not certified: the multipliers' bound " << result.dual_bound << " at radius "
            << radius << " is below -" << tolerance << " ("
            << std::count(undecided.begin(), undecided.end(), true)
            << " pairs near a switch; the MILP runs with ~mpcc_method active_set)";
    result.message = message.str();
    result.seconds = stopwatch.wallSeconds();
    return result;
  }
  LpRows lp;
  for (size_t i = 0; i < row_lower_.size(); ++i) lp.add(row_lower_[i], row_upper_[i]);
  for (int e = 0; e < jacobian_.nonzeros(); ++e) {
    lp.entry(jacobian_.rows[e], jacobian_.cols[e], jacobian_values_[e]);
  }
  std::vector<int> binary_of(pairs, -1);
  int binaries = 0;
  for (int p = 0; p < pairs; ++p) {
    const FixedPair& pair = pairs_[p];
    const double zero = linearValue(pair.zero_side, x_.data()),
                 other = linearValue(pair.other_side, x_.data());
    if (!undecided[p]) {
      // Decided: the zero side stays zero even where a variable of it was released elsewhere.
      bool touches_released = false;
      for (const LinearTerm& t : pair.zero_side) touches_released |= released[t.variable];
      if (touches_released)
        lp.addTerms(lp.add(std::min(-zero, 0.0), std::max(-zero, 0.0)), pair.zero_side);
      continue;
    }
    // z = 0: the zero side stays zero; z = 1: the other side vanishes, the zero side may grow.
    const int z = n + binaries;
    binary_of[p] = binaries++;
    const double zero_max = zero + range(pair.zero_side, low, high).second;
    const double other_max = other + range(pair.other_side, low, high).second;
    const int zero_bound = lp.add(-COIN_DBL_MAX, std::max(-zero, 0.0));  // zero + a^T d <= M z
    lp.addTerms(zero_bound, pair.zero_side);
    lp.entry(zero_bound, z, -std::max(zero_max, 0.0));
    const int other_bound = lp.add(-COIN_DBL_MAX, std::max(other_max - other, 0.0));
    lp.addTerms(other_bound, pair.other_side);  // other + b^T d <= M (1 - z)
    lp.entry(other_bound, z, std::max(other_max, 0.0));
    lp.addTerms(lp.add(std::min(-zero, 0.0), COIN_DBL_MAX), pair.zero_side);
    lp.addTerms(lp.add(std::min(-other, 0.0), COIN_DBL_MAX), pair.other_side);
  }
  result.undecided_pairs = binaries;
  std::vector<double> column_lower = low, column_upper = high, cost = gradient_;
  column_lower.resize(n + binaries, 0.0);
  column_upper.resize(n + binaries, 1.0);
  cost.resize(n + binaries, 0.0);
  std::vector<double> solution;
  result.solved =
      solveMilp(lp, column_lower, column_upper, cost, n, budget, result.value, solution);
  for (int p = 0; p < pairs; ++p) {
    const bool flipped = result.solved && binary_of[p] >= 0 && solution[n + binary_of[p]] > 0.5;
    result.left_is_zero[p] = pairs_[p].zero_side_is_left != flipped;
    result.other_branch |= flipped && !pairs_[p].biactive;
  }
  result.certified = result.solved && result.value >= -tolerance;
  std::ostringstream message;
  if (!result.solved) {
    message << "not certified: the LPEC was not solved within " << budget.max_nodes
            << " nodes (radius " << radius << ", " << binaries << " undecided pairs)";
  } else {
    message << "LPEC value " << result.value << " at radius " << radius << " (" << binaries
            << " undecided pairs): "
            << (result.certified      ? "B-stationary"
                : result.other_branch ? "descent on another branch"
                                      : "descent on its own branch (not solved to this precision)");
  }
  result.message = message.str();
  result.seconds = stopwatch.wallSeconds();
  return result;
}

}  // namespace fesd
