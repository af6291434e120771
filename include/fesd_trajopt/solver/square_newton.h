#pragma once

#include <string>
#include <vector>

#include "fesd_trajopt/nlp/nlp_problem.h"

namespace fesd {

struct NewtonOptions {
  int max_iterations = 20;
  /// Converged when every equality row holds to this (absolute; rows are in state and
  /// constraint units of order one) and the last step moved no variable by more than it.
  double tolerance = 1e-12;
};

struct NewtonResult {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;  ///< largest equality-row violation at the last point
  std::string failure;    ///< why not converged
};

/// Newton's method on the smooth square system an MPCC leaves once its active set is fixed
/// (RelaxedMpcc::fixGivenActiveSet): the equality rows (lower = upper) of `nlp` in its free
/// variables (lower < upper), with the exact sparse Jacobian and a sparse LU factorisation.
/// Fixed variables are set to their value first. Inequality rows and bounds are not imposed;
/// check them afterwards (constraintViolation). Fails without iterating when free variables and
/// equality rows differ in number, and when the Jacobian is singular.
NewtonResult solveSquareSystem(const NlpProblem& nlp, std::vector<double>& x,
                               const NewtonOptions& options = {});

/// The largest violation at x of the NLP's variable bounds and rows (0 when x is feasible).
double constraintViolation(const NlpProblem& nlp, const std::vector<double>& x);

}  // namespace fesd
