#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>
#include <Eigen/SparseCore>

#include "fesd_trajopt/nlp/nlp_problem.h"
#include "fesd_trajopt/solver/repeated_sparse_lu.h"

namespace fesd {

struct NewtonOptions {
  int max_iterations = 20;  ///< steps, with a new Jacobian or with the last one
  /// Converged when every equality row holds to this (absolute; rows are in state and
  /// constraint units of order one) and the last step moved no variable by more than it.
  double tolerance = 1e-12;
};

struct NewtonResult {
  bool converged = false;
  int iterations = 0;
  int factorizations = 0;  ///< Jacobians evaluated and factorised
  double residual = 0.0;   ///< largest equality-row violation at the last point
  int added_ties = 0;      ///< ties (VariableTie) that made the system determined
  std::string failure;     ///< why not converged
};

/// The derivatives of a solution of the system with respect to parameters of its fixed variables
/// (SquareNewton::derivatives).
struct SolutionDerivatives {
  bool defined = false;
  Eigen::MatrixXd values;  ///< per wanted variable (row), per parameter (column)
  double residual = 0.0;   ///< largest equation residual at the point
  std::string failure;     ///< why not defined
};

/// Two variables held equal when the equality rows leave more free variables than equations
/// and no row already holds them equal: FESD's equal steps at an element boundary where no
/// pair switches, which the step equilibration's sums can leave free (a force carried into a
/// step's start that the step's control released at once).
struct VariableTie {
  int first = -1, second = -1;
};

/// Newton's method on the smooth system an MPCC leaves once its active set is fixed
/// (RelaxedMpcc::fixGivenActiveSet): the equality rows (lower = upper) of `nlp` in its free
/// variables (lower < upper), with the exact sparse Jacobian and a sparse LU factorisation.
/// Fixed variables are set to their value first. Inequality rows and bounds are not imposed;
/// check them afterwards (constraintViolation).
///
/// Square systems are the rule. With more free variables than equations the ties are added
/// (those no row imposes yet); with more equations than free variables (several pairs switching
/// at one boundary, each adding an equation there) Newton runs on as many rows as there are
/// unknowns, picked by the factorisation's pivots, and converges only if the others hold too:
/// such a system has a solution only when its equations agree. Fails without iterating when
/// the equations stay fewer than the free variables, and when the Jacobian is singular.
///
/// A Jacobian, once factorised, serves the following steps (the chord method) while each step
/// shrinks at least tenfold, also into the next solve of the same system (the NLP's pattern,
/// free variables and equations: the integrator's steps of one active set, whose Jacobians
/// differ little); a step that does not reduce the residual, or shrinks too little, asks for a
/// new one at the current point. The convergence test is Newton's, so the solution is the same
/// to its tolerance. The factorisation's structure and pivots are kept for the next Jacobian
/// of the same system too (RepeatedSparseLu).
class SquareNewton {
 public:
  explicit SquareNewton(NewtonOptions options = {}) : options_(options) {}

  NewtonResult solve(const NlpProblem& nlp, std::vector<double>& x,
                     const std::vector<VariableTie>& ties = {});

  /// The implicit function theorem at a solution x of the system (the same equations and ties
  /// as solve()) by `parameters`, fixed variables: J_free dx_free/dp = -J(:, p) on the exact
  /// Jacobian at x, factorised afresh. Returns dx/dp for the `wanted` variables (free or fixed).
  /// With more equations than unknowns, the LU's pivot rows, as solve(). Not defined where the
  /// equations are fewer than the free variables or the Jacobian is singular. The residual says
  /// how well x solves the system and sits on its fixed variables' values.
  SolutionDerivatives derivatives(const NlpProblem& nlp, const std::vector<double>& x,
                                  const std::vector<VariableTie>& ties,
                                  const std::vector<int>& parameters,
                                  const std::vector<int>& wanted);

 private:
  /// With the system read (readSystem: `same_system`), the ties the rows do not impose at x; builds
  /// the matrix unless it is the last one's; false (with the failure) when it has fewer equations
  /// than free variables.
  bool prepareSystem(const NlpProblem& nlp, const std::vector<double>& x,
                     const std::vector<VariableTie>& ties, bool same_system, NewtonResult& result);
  /// The bounds, free variables and equations of `nlp` now; true when they and the Jacobian's
  /// pattern are those of the last solve (the system's matrix can be reused).
  bool readSystem(const NlpProblem& nlp);
  /// The ties that the equality rows do not impose already (judged by the Jacobian at hand).
  std::vector<VariableTie> missingTies(const NlpProblem& nlp,
                                       const std::vector<VariableTie>& ties) const;
  /// The matrix's structure and where each Jacobian entry and tie goes in it.
  void buildMatrix(const NlpProblem& nlp);
  /// The residual of the equations and ties at x into residual_; returns its largest magnitude.
  double evaluateResidual(const NlpProblem& nlp, const std::vector<double>& x);
  /// Evaluates the Jacobian at x and factorises it; false when singular.
  bool factorizeJacobian(const NlpProblem& nlp, const std::vector<double>& x);

  /// The chord method's bound on a step's size relative to the step before.
  static constexpr double kChordContraction = 0.1;

  NewtonOptions options_;
  std::vector<double> x_lower_, x_upper_, g_lower_, g_upper_, g_, jacobian_values_;
  std::vector<int> column_of_, equation_of_, free_variables_, equations_;
  std::vector<VariableTie> added_ties_;
  /// The pattern the matrix was built for, and its sizes.
  std::vector<int> pattern_rows_, pattern_cols_;
  std::vector<int> built_free_variables_, built_equations_;
  std::vector<VariableTie> built_ties_;
  bool has_matrix_ = false;
  bool factorized_ = false;  ///< lu_ holds a factorisation of a Jacobian of this system
  Eigen::SparseMatrix<double> matrix_;
  std::vector<int> value_slot_;  ///< per Jacobian entry: its slot in matrix_, or -1
  std::vector<double> residual_, previous_residual_, right_side_, step_, previous_free_values_;
  std::vector<int> parameter_of_;  ///< derivatives(): per variable, its parameter or -1
  RepeatedSparseLu lu_;
};

/// One Newton solve (SquareNewton) without ties.
NewtonResult solveSquareSystem(const NlpProblem& nlp, std::vector<double>& x,
                               const NewtonOptions& options = {});

/// The largest violation at x of the NLP's variable bounds and rows but `skipped_rows` (0 when x
/// is feasible; infinity when they cannot be evaluated or are not finite).
double constraintViolation(const NlpProblem& nlp, const std::vector<double>& x,
                           const std::vector<int>& skipped_rows = {});

}  // namespace fesd
