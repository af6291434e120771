#pragma once

#include <vector>

#include "fesd_trajopt/discretization/collocation_discretization.h"
#include "fesd_trajopt/model/dcs_model.h"

namespace fesd {

/// The FESD (or, with switch detection off, the standard fixed-step) discretisation of an
/// OcpDefinition as a relaxable MPCC (Pozharskiy et al. 2024, Sec. III):
///  - Runge-Kutta equations of every finite element (eq. 6a),
///  - lifted constraint values s = c(x) at every stage point and s >= 0, lambda >= 0,
///  - complementarity: per stage (standard) or cross-complementarity (eq. 8) in the chosen form,
///  - step equilibration (Sec. III-C): imposed exactly by active-set polishing (Table I: equal
///    steps at every boundary without a switch) and, in the relaxed NLPs, guided by a vanishing
///    step regulariser; or (kBigM) the paper's nu = (sum_c B v sum_c F) ^ (sum_l B v sum_l F),
///    max through the KKT conditions of its LP, OR over the constraints, and the big-M bound,
///  - sum of steps = interval length and step bounds,
///  - costs by the RK quadrature, control/state bounds, path and terminal constraints.
/// The start state and the controls are NLP variables, fixed or bounded through their bounds,
/// so one structure serves optimal control and simulation alike.
class PdsDiscretization : public CollocationDiscretization {
 public:
  PdsDiscretization(OcpDefinition ocp, DiscretizationOptions options);

  /// Fixes the start state (bounds and guess) and updates its lifted constraint values.
  void setInitialState(const Eigen::VectorXd& x0) override;
  /// Sets lambda just before the start (default 0), e.g. to the end of a previous simulation step.
  void setInitialMultipliers(const Eigen::VectorXd& lambda0);
  /// lambda before the start: the previous step's last stage multipliers. With the same
  /// dynamics, a pair in contact at the start keeps them on the lambda side of the first
  /// element's cross-complementarity (eq. 8c across the step boundary): lambda is continuous at
  /// a release, so the pair cannot let go right at the step's start, only at an element
  /// boundary inside it. Without this, two releases in one step of two elements let the solver
  /// release one of them at the step's start, early (measured: 2e-3 early, state error 4e-6,
  /// not flagged, on a random push scene), instead of failing the step.
  void continueFrom(const Trajectory& previous, bool same_dynamics) override;

  /// A guess with every state at the start state, lambda = 0, nominal steps and the given
  /// controls (clipped to their bounds; empty means 0); auxiliaries made consistent.
  std::vector<double> constantGuess(
      const std::vector<Eigen::VectorXd>& controls = {}) const override;
  /// States, lambda (clipped at 0) and controls of the guess on the nominal grid; s = c(x),
  /// clipped at 0 where a planned path grazes into a constraint.
  std::vector<double> guessFrom(const TrajectoryGuess& guess) const override;
  /// The solution of a previous, equally structured problem moved to the current start state:
  /// every stage state shifted by (start - old start), c(x) re-evaluated, lambda and steps kept.
  /// A simulation step's guess from the step before (smooth motion repeats its increments).
  std::vector<double> translatedGuess(const std::vector<double>& previous_solution) const override;

  /// The element's polynomial's closest approach (closestApproach) within `tolerance`.
  bool grazesBetweenStages(const Trajectory& piece, int element, int pair,
                           double tolerance) const override;

  /// The last stage's lambda of a pair released at a boundary inside a control interval where
  /// another pair's contact begins.
  std::vector<int> jumpingForces(const PairModes& modes) const override;

  /// lambda = max(0, -grad c . f / |grad c|^2) is continuous where f is: it falls to zero at a
  /// release, and the velocity does not jump (unless another pair's contact at that instant
  /// makes it jump: jumpingForces; such a switch coincides with the contact's).
  bool releasesAreSmooth() const override { return true; }

  /// c_k(x) <= tolerance.
  std::vector<bool> activeAt(const Eigen::VectorXd& x, double tolerance) const override;

 private:
  struct StagePoint {
    int x = -1, s = -1, lambda = -1;  ///< first indices of the point's x, s = c(x), lambda
  };
  /// The backward (element n-1) and forward (element n) sums of one constraint at a boundary.
  struct BoundarySums {
    LinearExpression lambda_backward, lambda_forward, c_backward, c_forward;
  };
  /// One boundary between elements of a control interval: its sums and, with kBigM, the
  /// auxiliaries of the paper's formulation (empty, any_switch = -1, otherwise).
  struct EquilibrationAuxiliaries {
    int previous_element, element;
    std::vector<BoundarySums> sums;                           ///< per constraint
    std::vector<int> pi_lambda, pi_c, maximum, gap, kkt, nu;  ///< per constraint (gap, kkt: 2)
    int any_switch;                                           ///< OR of nu over the constraints
    int equal_steps_row;  ///< h_{n-1} - h_n, free except when polishing a boundary without switch
  };

  void buildVariables();
  void buildDynamics();
  void buildComplementarity();
  void buildStepEquilibration();
  /// Rows c_k(x(fraction)) >= 0 on the element's polynomial for every gap guard.
  void buildGapGuards();
  /// Rows g_f(x, u, lambda) <= 0 at every stage point (OcpDefinition::force_constraints).
  void buildForceConstraints();
  /// The paper's auxiliaries (pi, max, nu, OR) and big-M rows at every boundary (kBigM).
  void addBigMEquilibration();
  /// The polishing counterpart of step equilibration (NlpAssembly's active-set hook): with the
  /// complementarity sides fixed, nu > 0 exactly when some c and some lambda in a boundary's
  /// sums are nonzero (Table I); h_{n-1} = h_n at the boundaries without a switch. The kBigM
  /// auxiliaries' inequalities would pin them without interior, so they are frozen.
  void equilibrateActiveSet(const double* x);
  void addLifting(const StagePoint& point);
  /// A guess's lambda (clipped at 0) and s = c(x) (clipped at 0: a path may graze into a
  /// constraint) at one stage point whose state is set.
  void setPairGuess(const StagePoint& point, const Eigen::VectorXd& lambda,
                    std::vector<double>& x) const;
  void guessPairValues(const Trajectory& trajectory, std::vector<double>& x) const override;
  /// The point before an element's stages: the start or the previous element's last stage.
  const StagePoint& previousPoint(int element) const;
  /// Sets the step-equilibration auxiliaries (pi, max, nu, OR) of x consistently with its
  /// s and lambda values, so a guess starts (nearly) feasible for them.
  void completeDependentVariables(std::vector<double>& x) const override;
  int numPairs() const override { return nc_; }
  /// lambda and s = c(x) at the stages, and c's lowest value between them.
  void readPairValues(const double* x, Trajectory& trajectory) const override;
  /// c(x_start) <= tolerance.
  std::vector<bool> activeAtStart(const double* x, const Trajectory& trajectory,
                                  double tolerance) const override;

  std::shared_ptr<const DcsModel> model_;
  int nc_;
  StagePoint start_;  ///< s and lambda of the start; its x is start_state_
  /// Data: lambda carried over a step boundary for continuity (continueFrom), else 0.
  int carried_lambda_ = -1;
  std::vector<std::vector<StagePoint>> stages_;  ///< per element, per stage
  std::vector<EquilibrationAuxiliaries> equilibration_;
  int auxiliary_variables_begin_ = 0, auxiliary_variables_end_ = 0;  ///< [begin, end)
  int auxiliary_rows_begin_ = 0, auxiliary_rows_end_ = 0;
};

}  // namespace fesd
