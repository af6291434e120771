#pragma once

#include <vector>

#include "fesd_trajopt/function/smooth_function.h"

namespace fesd {

/// One variable and its coefficient in a linear expression.
struct LinearTerm {
  int variable;
  double coefficient;
};
using LinearExpression = std::vector<LinearTerm>;

/// The expression's value at x.
inline double linearValue(const LinearExpression& expression, const double* x) {
  double value = 0.0;
  for (const LinearTerm& t : expression) value += t.coefficient * x[t.variable];
  return value;
}

/// A complementarity pair under a fixed active set: the side fixed to zero and the other one,
/// or, for a pair left biactive, both sides free (`zero_side` is then its left side).
struct FixedPair {
  LinearExpression zero_side, other_side;
  bool zero_side_is_left = true;
  bool biactive = false;
};

/// A sparse nonlinear program  min f(x)  s.t.  g_l <= g(x) <= g_u,  x_l <= x <= x_u,
/// with exact first and second derivatives. Solver-agnostic: the Ipopt adapter reads it.
class NlpProblem {
 public:
  virtual ~NlpProblem() = default;

  virtual int numVariables() const = 0;
  virtual int numConstraints() const = 0;
  virtual void getBounds(double* x_lower, double* x_upper, double* g_lower,
                         double* g_upper) const = 0;

  virtual double objective(const double* x) const = 0;
  virtual void objectiveGradient(const double* x, double* gradient) const = 0;
  virtual void constraints(const double* x, double* g) const = 0;

  virtual const SparsityPattern& jacobianPattern() const = 0;
  virtual void jacobian(const double* x, double* values) const = 0;
  /// Lower triangle of  objective_factor * Hess f + sum_i multipliers_i * Hess g_i.
  virtual const SparsityPattern& hessianPattern() const = 0;
  virtual void hessian(const double* x, double objective_factor, const double* multipliers,
                       double* values) const = 0;
};

/// grad f(x) + J(x)^T multipliers: the gradient of the Lagrangian f + multipliers^T g.
inline std::vector<double> lagrangianGradient(const NlpProblem& problem, const double* x,
                                              const double* multipliers) {
  std::vector<double> gradient(problem.numVariables());
  problem.objectiveGradient(x, gradient.data());
  const SparsityPattern& pattern = problem.jacobianPattern();
  std::vector<double> values(pattern.nonzeros());
  problem.jacobian(x, values.data());
  for (int e = 0; e < pattern.nonzeros(); ++e) {
    gradient[pattern.cols[e]] += multipliers[pattern.rows[e]] * values[e];
  }
  return gradient;
}

/// An MPCC relaxed by a parameter sigma >= 0 (sigma = 0 is the MPCC itself).
class RelaxedMpcc : public NlpProblem {
 public:
  virtual void setRelaxation(double sigma) = 0;
  virtual double relaxation() const = 0;
  /// Weight of objective terms that vanish with sigma (regularisers of the relaxed NLPs);
  /// 0 removes them.
  virtual void setVanishingTermsWeight(double weight) = 0;
  virtual int numComplementarities() const = 0;
  /// Constraint rows of the complementarity products.
  virtual const std::vector<int>& complementarityRows() const = 0;
  /// Active-set polishing: fixes, through variable bounds, the side of every complementarity
  /// pair that is zero at x (the smaller one, unless it holds a fixed nonzero term) and drops
  /// the pair, leaving a smooth NLP whose solutions satisfy the complementarity exactly. `flip`
  /// >= 0 reverses the choice for the flip-th most ambiguous pair (largest min/max ratio of its
  /// two sides), for a retry after a failed attempt. Returns false (and changes nothing) when a
  /// zero side is not a sum of nonnegative free variables, when both sides of a pair hold fixed
  /// nonzero terms, or when there is no such ambiguous pair to flip.
  virtual bool fixActiveSet(const double* x, int flip = -1) = 0;
  /// Biactive pairs in identifyActiveSet and fixActiveSet: with `fraction` > 0, a pair whose two
  /// sides are both at most `fraction` times the relaxation's scale at `sigma` (the size both
  /// sides of a product at the bound sigma would have) is biactive: fixActiveSet fixes neither
  /// side and drops its product row, leaving the pair's part of the relaxed NLP (both sides >= 0),
  /// and identifyActiveSet reports it as a right-side zero. 0 (default): every pair has a zero
  /// side. Implementations without biactive pairs may ignore it.
  virtual void setBiactiveRule(double fraction, double sigma) {
    (void)fraction;
    (void)sigma;
  }
  /// The choice fixActiveSet(x) makes: per pair, whether its left side is the one fixed to zero;
  /// empty when fixActiveSet would refuse.
  virtual std::vector<bool> identifyActiveSet(const double* x) const = 0;
  /// fixActiveSet with the choice given (per pair: the left side is the zero one); x is the
  /// point the active-set hook sees. False (nothing changed) when a zero side holds nonzero data.
  virtual bool fixGivenActiveSet(const std::vector<bool>& left_is_zero, const double* x) = 0;
  /// While an active set is fixed: the same choice with every pair flipped whose free side is
  /// (nearly) zero at x too, e.g. the last point of a polishing solve that failed because a
  /// fixed contact needed a negative force (a release just before a step's end: the solve
  /// leaves lambda at its bound). Empty when no pair is biactive.
  virtual std::vector<bool> flipBiactivePairs(const double* x) const = 0;
  /// Undoes fixActiveSet.
  virtual void releaseActiveSet() = 0;
  /// While an active set is fixed: every pair's sides as it fixes them (the LPEC's data).
  virtual std::vector<FixedPair> fixedPairs() const = 0;
  /// While an active set is fixed: the variable bounds of the MPCC, before it was fixed.
  virtual void boundsBeforeActiveSet(double* x_lower, double* x_upper) const = 0;
  /// While an active set is fixed: how far a solution (x and its constraint multipliers, for the
  /// Lagrangian f + multipliers^T g) is from B-stationarity of the MPCC. At a pair whose free
  /// side vanishes too (biactive), releasing the fixed side is feasible; its variables must not
  /// offer descent, i.e. d(Lagrangian)/dx_v >= 0 for each of them. Returns the largest
  /// -d(Lagrangian)/dx_v over those variables, relative to max(1, |grad f|_inf); 0 if none.
  virtual double biactiveDescent(const double* x, const double* multipliers) const = 0;
  /// Largest violation of the complementarity constraints at x (0 when they hold exactly).
  virtual double complementarityResidual(const double* x) const = 0;
};

}  // namespace fesd
