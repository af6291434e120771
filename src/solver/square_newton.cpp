#include "fesd_trajopt/solver/square_newton.h"

#include <algorithm>
#include <cmath>

#include <Eigen/SparseCore>
#include <Eigen/SparseLU>

namespace fesd {
namespace {

struct Bounds {
  std::vector<double> x_lower, x_upper, g_lower, g_upper;

  explicit Bounds(const NlpProblem& nlp)
      : x_lower(nlp.numVariables()),
        x_upper(nlp.numVariables()),
        g_lower(nlp.numConstraints()),
        g_upper(nlp.numConstraints()) {
    nlp.getBounds(x_lower.data(), x_upper.data(), g_lower.data(), g_upper.data());
  }
};

}  // namespace

NewtonResult solveSquareSystem(const NlpProblem& nlp, std::vector<double>& x,
                               const NewtonOptions& options) {
  const Bounds bounds(nlp);
  const int n = nlp.numVariables(), m = nlp.numConstraints();
  std::vector<int> column_of(n, -1), equation_of(m, -1), free_variables, equations;
  for (int v = 0; v < n; ++v) {
    if (bounds.x_lower[v] == bounds.x_upper[v]) {
      x[v] = bounds.x_lower[v];
    } else {
      column_of[v] = static_cast<int>(free_variables.size());
      free_variables.push_back(v);
    }
  }
  for (int row = 0; row < m; ++row) {
    if (bounds.g_lower[row] == bounds.g_upper[row]) {
      equation_of[row] = static_cast<int>(equations.size());
      equations.push_back(row);
    }
  }
  NewtonResult result;
  if (free_variables.size() != equations.size()) {
    result.failure = "not square: " + std::to_string(free_variables.size()) + " free variables, " +
                     std::to_string(equations.size()) + " equations";
    return result;
  }
  const int size = static_cast<int>(equations.size());
  const SparsityPattern& pattern = nlp.jacobianPattern();
  std::vector<double> g(m), values(pattern.nonzeros());
  Eigen::VectorXd residual(size);
  auto evaluate_residual = [&] {
    nlp.constraints(x.data(), g.data());
    for (int i = 0; i < size; ++i) residual(i) = g[equations[i]] - bounds.g_lower[equations[i]];
    result.residual = size ? residual.lpNorm<Eigen::Infinity>() : 0.0;
  };
  evaluate_residual();
  Eigen::SparseLU<Eigen::SparseMatrix<double>, Eigen::COLAMDOrdering<int>> lu;
  std::vector<Eigen::Triplet<double>> triplets;
  Eigen::SparseMatrix<double> jacobian(size, size);
  for (; result.iterations < options.max_iterations; ++result.iterations) {
    if (!std::isfinite(result.residual)) {
      result.failure = "the residual is not finite";
      return result;
    }
    nlp.jacobian(x.data(), values.data());
    triplets.clear();
    for (int e = 0; e < pattern.nonzeros(); ++e) {
      const int i = equation_of[pattern.rows[e]], j = column_of[pattern.cols[e]];
      if (i >= 0 && j >= 0) triplets.emplace_back(i, j, values[e]);
    }
    // The same entries in every iteration: the ordering and symbolic analysis are done once.
    jacobian.setFromTriplets(triplets.begin(), triplets.end());
    if (result.iterations == 0) lu.analyzePattern(jacobian);
    lu.factorize(jacobian);
    if (lu.info() != Eigen::Success) {
      result.failure = "singular Jacobian";
      return result;
    }
    const Eigen::VectorXd step = lu.solve(-residual);
    for (int j = 0; j < size; ++j) x[free_variables[j]] += step(j);
    evaluate_residual();
    // Rounding in rows of large terms (c = |p|^2 - R^2 far from the origin) scales with |x|.
    double scale = 1.0;
    for (int v : free_variables) scale = std::max(scale, std::fabs(x[v]));
    if (result.residual <= options.tolerance * scale &&
        step.lpNorm<Eigen::Infinity>() <= 1e3 * options.tolerance * scale) {
      result.converged = true;
      ++result.iterations;
      return result;
    }
  }
  result.failure = "no convergence in " + std::to_string(options.max_iterations) + " iterations";
  return result;
}

double constraintViolation(const NlpProblem& nlp, const std::vector<double>& x) {
  const Bounds bounds(nlp);
  std::vector<double> g(nlp.numConstraints());
  nlp.constraints(x.data(), g.data());
  double violation = 0.0;
  auto outside = [](double value, double lower, double upper) {
    return std::max({lower - value, value - upper, 0.0});
  };
  for (size_t v = 0; v < x.size(); ++v) {
    violation = std::max(violation, outside(x[v], bounds.x_lower[v], bounds.x_upper[v]));
  }
  for (size_t row = 0; row < g.size(); ++row) {
    violation = std::max(violation, outside(g[row], bounds.g_lower[row], bounds.g_upper[row]));
  }
  return violation;
}

}  // namespace fesd
