#include "fesd_trajopt/solver/square_newton.h"

#include <algorithm>
#include <cmath>
#include <exception>
#include <limits>

namespace fesd {

bool SquareNewton::readSystem(const NlpProblem& nlp) {
  const int n = nlp.numVariables(), m = nlp.numConstraints();
  x_lower_.resize(n);
  x_upper_.resize(n);
  g_lower_.resize(m);
  g_upper_.resize(m);
  nlp.getBounds(x_lower_.data(), x_upper_.data(), g_lower_.data(), g_upper_.data());
  column_of_.assign(n, -1);
  equation_of_.assign(m, -1);
  free_variables_.clear();
  equations_.clear();
  for (int v = 0; v < n; ++v) {
    if (x_lower_[v] != x_upper_[v]) {
      column_of_[v] = static_cast<int>(free_variables_.size());
      free_variables_.push_back(v);
    }
  }
  for (int row = 0; row < m; ++row) {
    if (g_lower_[row] == g_upper_[row]) {
      equation_of_[row] = static_cast<int>(equations_.size());
      equations_.push_back(row);
    }
  }
  const SparsityPattern& pattern = nlp.jacobianPattern();
  return has_matrix_ && free_variables_ == built_free_variables_ &&
         equations_ == built_equations_ && pattern.rows == pattern_rows_ &&
         pattern.cols == pattern_cols_;
}

std::vector<VariableTie> SquareNewton::missingTies(const NlpProblem& nlp,
                                                   const std::vector<VariableTie>& ties) const {
  const SparsityPattern& pattern = nlp.jacobianPattern();
  // An equation a x_first - a x_second = 0 in these two free variables alone imposes a tie.
  auto imposed = [&](const VariableTie& tie) {
    for (int e = 0; e < pattern.nonzeros(); ++e) {
      const int row = pattern.rows[e];
      if (pattern.cols[e] != tie.first || equation_of_[row] < 0 || g_lower_[row] != 0.0) continue;
      int entries = 0;
      double first = 0.0, second = 0.0;
      for (int f = 0; f < pattern.nonzeros(); ++f) {
        if (pattern.rows[f] != row || column_of_[pattern.cols[f]] < 0) continue;
        ++entries;
        if (pattern.cols[f] == tie.first) first = jacobian_values_[f];
        if (pattern.cols[f] == tie.second) second = jacobian_values_[f];
      }
      if (entries == 2 && first != 0.0 && first == -second) return true;
    }
    return false;
  };
  std::vector<VariableTie> missing;
  for (const VariableTie& tie : ties) {
    if (column_of_[tie.first] >= 0 && column_of_[tie.second] >= 0 && !imposed(tie)) {
      missing.push_back(tie);
    }
  }
  return missing;
}

void SquareNewton::buildMatrix(const NlpProblem& nlp) {
  const SparsityPattern& pattern = nlp.jacobianPattern();
  const int equations = static_cast<int>(equations_.size());
  std::vector<Eigen::Triplet<double>> entries;
  for (int e = 0; e < pattern.nonzeros(); ++e) {
    const int i = equation_of_[pattern.rows[e]], j = column_of_[pattern.cols[e]];
    if (i >= 0 && j >= 0) entries.emplace_back(i, j, 0.0);
  }
  for (size_t t = 0; t < added_ties_.size(); ++t) {
    const int row = equations + static_cast<int>(t);
    entries.emplace_back(row, column_of_[added_ties_[t].first], 1.0);
    entries.emplace_back(row, column_of_[added_ties_[t].second], -1.0);
  }
  matrix_.resize(equations + static_cast<int>(added_ties_.size()),
                 static_cast<int>(free_variables_.size()));
  matrix_.setFromTriplets(entries.begin(), entries.end());
  matrix_.makeCompressed();
  value_slot_.assign(pattern.nonzeros(), -1);
  const int* starts = matrix_.outerIndexPtr();
  const int* rows = matrix_.innerIndexPtr();
  for (int e = 0; e < pattern.nonzeros(); ++e) {
    const int i = equation_of_[pattern.rows[e]], j = column_of_[pattern.cols[e]];
    if (i < 0 || j < 0) continue;
    value_slot_[e] =
        static_cast<int>(std::lower_bound(rows + starts[j], rows + starts[j + 1], i) - rows);
  }
  pattern_rows_ = pattern.rows;
  pattern_cols_ = pattern.cols;
  built_free_variables_ = free_variables_;
  built_equations_ = equations_;
  built_ties_ = added_ties_;
  has_matrix_ = true;
}

double SquareNewton::evaluateResidual(const NlpProblem& nlp, const std::vector<double>& x) {
  g_.resize(nlp.numConstraints());
  nlp.constraints(x.data(), g_.data());
  const size_t equations = equations_.size();
  residual_.resize(equations + added_ties_.size());
  for (size_t i = 0; i < equations; ++i) residual_[i] = g_[equations_[i]] - g_lower_[equations_[i]];
  for (size_t t = 0; t < added_ties_.size(); ++t) {
    residual_[equations + t] = x[added_ties_[t].first] - x[added_ties_[t].second];
  }
  double largest = 0.0;
  for (double r : residual_) {
    if (!std::isfinite(r)) return std::numeric_limits<double>::infinity();
    largest = std::max(largest, std::fabs(r));
  }
  return largest;
}

bool SquareNewton::factorizeJacobian(const NlpProblem& nlp, const std::vector<double>& x) {
  nlp.jacobian(x.data(), jacobian_values_.data());
  double* values = matrix_.valuePtr();
  for (size_t e = 0; e < value_slot_.size(); ++e) {
    if (value_slot_[e] >= 0) values[value_slot_[e]] = jacobian_values_[e];
  }
  factorized_ = lu_.factorize(matrix_);
  return factorized_;
}

bool SquareNewton::prepareSystem(const NlpProblem& nlp, const std::vector<double>& x,
                                 const std::vector<VariableTie>& ties, bool same_system,
                                 NewtonResult& result) {
  const int unknowns = static_cast<int>(free_variables_.size());
  jacobian_values_.resize(nlp.jacobianPattern().nonzeros());
  added_ties_.clear();
  if (unknowns > static_cast<int>(equations_.size()) && !ties.empty()) {
    nlp.jacobian(x.data(), jacobian_values_.data());
    added_ties_ = missingTies(nlp, ties);
  }
  result.added_ties = static_cast<int>(added_ties_.size());
  const int rows = static_cast<int>(equations_.size() + added_ties_.size());
  if (rows < unknowns) {
    result.failure = "not square: " + std::to_string(unknowns) + " free variables, " +
                     std::to_string(rows) + " equations";
    return false;
  }
  const bool same_ties = added_ties_.size() == built_ties_.size() &&
                         std::equal(added_ties_.begin(), added_ties_.end(), built_ties_.begin(),
                                    [](const VariableTie& a, const VariableTie& b) {
                                      return a.first == b.first && a.second == b.second;
                                    });
  if (!same_system || !same_ties) {
    buildMatrix(nlp);
    factorized_ = false;
  }
  return true;
}

NewtonResult SquareNewton::solve(const NlpProblem& nlp, std::vector<double>& x,
                                 const std::vector<VariableTie>& ties) {
  NewtonResult result;
  const bool same_system = readSystem(nlp);
  for (size_t v = 0; v < x.size(); ++v) {
    if (column_of_[v] < 0) x[v] = x_lower_[v];
  }
  if (!prepareSystem(nlp, x, ties, same_system, result)) return result;
  const int unknowns = static_cast<int>(free_variables_.size());
  const int rows = static_cast<int>(equations_.size() + added_ties_.size());
  result.residual = evaluateResidual(nlp, x);
  bool fresh = false;  // lu_ factorises the Jacobian at the current x
  double last_step = std::numeric_limits<double>::infinity();
  for (; result.iterations < options_.max_iterations; ++result.iterations) {
    if (!std::isfinite(result.residual)) {
      result.failure = "the residual is not finite";
      return result;
    }
    if (!factorized_) {
      ++result.factorizations;
      if (!factorizeJacobian(nlp, x)) {
        result.failure = "singular Jacobian";
        return result;
      }
      fresh = true;
    }
    right_side_.resize(rows);
    for (int i = 0; i < rows; ++i) right_side_[i] = -residual_[i];
    lu_.solve(right_side_, step_);
    previous_free_values_.resize(unknowns);
    double step_size = 0.0;
    for (int j = 0; j < unknowns; ++j) {
      previous_free_values_[j] = x[free_variables_[j]];
      x[free_variables_[j]] += step_[j];
      step_size = std::max(step_size, std::fabs(step_[j]));
    }
    residual_.swap(previous_residual_);
    const double residual = evaluateResidual(nlp, x);
    if (!fresh && !(residual <= result.residual)) {
      // An old Jacobian that does not even reduce the residual: back, and a new one here.
      for (int j = 0; j < unknowns; ++j) x[free_variables_[j]] = previous_free_values_[j];
      residual_.swap(previous_residual_);
      factorized_ = false;
      continue;
    }
    result.residual = residual;
    // Rounding in rows of large terms (c = |p|^2 - R^2 far from the origin) scales with |x|.
    double scale = 1.0;
    for (int v : free_variables_) scale = std::max(scale, std::fabs(x[v]));
    // A Newton step of 1e-9 leaves an error of its square; a chord step (contracting tenfold
    // or better) one of its own size, so it must be as small as the tolerance.
    const bool settled = step_size <= (fresh ? 1e3 : 1.0) * options_.tolerance * scale;
    if (settled && result.residual <= options_.tolerance * scale) {
      result.converged = true;
      ++result.iterations;
      return result;
    }
    if (settled && rows > unknowns) {
      // Settled on the pivot rows' root: the other rows' residual is their disagreement.
      double pivot_rows_residual = 0.0;
      for (int i = 0; i < rows; ++i) {
        if (lu_.pivoted(i))
          pivot_rows_residual = std::max(pivot_rows_residual, std::fabs(residual_[i]));
      }
      if (pivot_rows_residual <= options_.tolerance * scale) {
        ++result.iterations;
        result.failure = "the equations disagree: " + std::to_string(rows) + " for " +
                         std::to_string(unknowns) + " free variables, residual " +
                         std::to_string(result.residual) + " at the root of as many of them";
        return result;
      }
    }
    if (!fresh && step_size > kChordContraction * last_step) factorized_ = false;
    fresh = false;
    last_step = step_size;
  }
  result.failure = "no convergence in " + std::to_string(options_.max_iterations) + " iterations";
  return result;
}

SolutionDerivatives SquareNewton::derivatives(const NlpProblem& nlp, const std::vector<double>& x,
                                              const std::vector<VariableTie>& ties,
                                              const std::vector<int>& parameters,
                                              const std::vector<int>& wanted) {
  SolutionDerivatives result;
  NewtonResult system;
  if (!prepareSystem(nlp, x, ties, readSystem(nlp), system)) {
    result.failure = system.failure;
    return result;
  }
  const int rows = static_cast<int>(equations_.size() + added_ties_.size());
  result.residual = evaluateResidual(nlp, x);
  for (size_t v = 0; v < x.size(); ++v) {
    if (column_of_[v] < 0)
      result.residual = std::max(result.residual, std::fabs(x[v] - x_lower_[v]));
  }
  if (!factorizeJacobian(nlp, x)) {
    result.failure = "singular Jacobian";
    return result;
  }
  // J_free dx_free/dp = -J(:, p) for every parameter p at once (row-major right sides): the
  // Jacobian's columns of the parameters' variables, in the equations (not the ties).
  const int count = static_cast<int>(parameters.size());
  parameter_of_.assign(nlp.numVariables(), -1);
  for (int p = 0; p < count; ++p) parameter_of_[parameters[p]] = p;
  right_side_.assign(static_cast<size_t>(rows) * count, 0.0);
  const SparsityPattern& pattern = nlp.jacobianPattern();
  for (int e = 0; e < pattern.nonzeros(); ++e) {
    const int equation = equation_of_[pattern.rows[e]], p = parameter_of_[pattern.cols[e]];
    if (equation >= 0 && p >= 0) right_side_[equation * count + p] -= jacobian_values_[e];
  }
  lu_.solve(right_side_, step_, count);
  result.values.resize(static_cast<int>(wanted.size()), count);
  for (size_t w = 0; w < wanted.size(); ++w) {
    const int column = column_of_[wanted[w]], own = parameter_of_[wanted[w]];
    for (int p = 0; p < count; ++p) {
      result.values(static_cast<int>(w), p) = column >= 0 ? step_[column * count + p]
                                              : own == p  ? 1.0
                                                          : 0.0;
    }
  }
  result.defined = true;
  return result;
}

NewtonResult solveSquareSystem(const NlpProblem& nlp, std::vector<double>& x,
                               const NewtonOptions& options) {
  return SquareNewton(options).solve(nlp, x);
}

double constraintViolation(const NlpProblem& nlp, const std::vector<double>& x,
                           const std::vector<int>& skipped_rows) {
  const int n = nlp.numVariables(), m = nlp.numConstraints();
  if (static_cast<int>(x.size()) != n) return std::numeric_limits<double>::infinity();
  std::vector<double> x_lower(n), x_upper(n), g_lower(m), g_upper(m), g(m);
  try {
    nlp.getBounds(x_lower.data(), x_upper.data(), g_lower.data(), g_upper.data());
    nlp.constraints(x.data(), g.data());
  } catch (const std::exception&) {
    return std::numeric_limits<double>::infinity();
  }
  double violation = 0.0;
  auto outside = [](double value, double lower, double upper) {
    return std::max({lower - value, value - upper, 0.0});
  };
  for (int v = 0; v < n; ++v)
    violation = std::max(violation, outside(x[v], x_lower[v], x_upper[v]));
  for (int row = 0; row < m; ++row) {
    if (std::count(skipped_rows.begin(), skipped_rows.end(), row)) continue;
    violation = std::max(violation, outside(g[row], g_lower[row], g_upper[row]));
  }
  return std::isnan(violation) ? std::numeric_limits<double>::infinity() : violation;
}

}  // namespace fesd
