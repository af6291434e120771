#pragma once

#include <vector>

#include "fesd_trajopt/discretization/butcher_tableau.h"
#include "fesd_trajopt/discretization/collocation_grid.h"
#include "fesd_trajopt/discretization/discretization.h"
#include "fesd_trajopt/model/dcs_model.h"

namespace fesd {

/// The FESD (or, with switch detection off, the standard fixed-step) discretisation of an
/// OcpDefinition as a relaxable MPCC (seed 000, Sec. III):
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
class PdsDiscretization : public Discretization {
 public:
  PdsDiscretization(OcpDefinition ocp, DiscretizationOptions options);
  // The NLP's active-set hook refers to this object: it stays where it was built.
  PdsDiscretization(const PdsDiscretization&) = delete;
  PdsDiscretization& operator=(const PdsDiscretization&) = delete;

  NlpAssembly& nlp() override { return nlp_; }
  const NlpAssembly& nlp() const override { return nlp_; }
  const OcpDefinition& ocp() const { return ocp_; }
  const DiscretizationOptions& options() const { return options_; }
  const ButcherTableau& tableau() const { return tableau_; }
  /// True when element lengths are free (FESD on and the model has constraints).
  bool stepsAreFree() const override { return steps_free_; }
  int numElements() const { return static_cast<int>(stages_.size()); }  ///< all intervals
  double nominalStep() const { return nominal_step_; }

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
  /// Fixes the control of interval k to u (simulation).
  void fixControl(int interval, const Eigen::VectorXd& u) override;
  /// Frees the control of interval k within the OCP's control bounds.
  void freeControl(int interval);

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
  /// A solution of a discretisation of the same OCP with the same grid sizes (e.g. the
  /// standard method's) as a guess for this one: shared variables copied, auxiliaries completed.
  std::vector<double> adoptedGuess(const Discretization& other,
                                   const std::vector<double>& solution) const override;
  /// Sets the step-equilibration auxiliaries (pi, max, nu, OR) of x consistently with its
  /// s and lambda values, so a guess starts (nearly) feasible for them.
  void completeAuxiliaries(std::vector<double>& x) const;

  /// Reads the trajectory (times, states, stage values, controls, switches) from a solution;
  /// times start at start_time.
  Trajectory extract(const double* x, double start_time = 0.0,
                     double activity_tolerance = kDefaultActivityTolerance,
                     double penetration_tolerance = kDefaultPenetrationTolerance) const override;
  /// c_k(x) <= tolerance.
  std::vector<bool> activeAt(const Eigen::VectorXd& x, double tolerance) const override;

  int controlIndex(int interval) const { return grid_.controls[interval]; }
  int stepIndex(int element) const { return grid_.steps[element]; }
  int stateIndex(int element, int stage) const { return stages_[element][stage].x; }
  int startStateIndex() const { return start_.x; }

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
  /// The paper's auxiliaries (pi, max, nu, OR) and big-M rows at every boundary (kBigM).
  void addBigMEquilibration();
  /// The polishing counterpart of step equilibration (NlpAssembly's active-set hook): with the
  /// complementarity sides fixed, nu > 0 exactly when some c and some lambda in a boundary's
  /// sums are nonzero (Table I); h_{n-1} = h_n at the boundaries without a switch. The kBigM
  /// auxiliaries' inequalities would pin them without interior, so they are frozen.
  void equilibrateActiveSet(const double* x);
  void addLifting(const StagePoint& point);
  const StagePoint& previousPoint(int element) const;
  std::vector<int> velocityInputs(int element, int stage) const;

  OcpDefinition ocp_;
  std::shared_ptr<const DcsModel> model_;
  DiscretizationOptions options_;
  ButcherTableau tableau_;
  int nx_, nu_, nc_;
  double nominal_step_;
  bool steps_free_;
  NlpAssembly nlp_;
  StagePoint start_;
  /// Data: lambda carried over a step boundary for continuity (continueFrom), else 0.
  int carried_lambda_ = -1;
  CollocationGrid grid_;
  std::vector<std::vector<StagePoint>> stages_;  ///< per element, per stage
  std::vector<EquilibrationAuxiliaries> equilibration_;
  int core_variables_ = 0;  ///< start, controls, steps, stage points: the same in any method
  int auxiliary_variables_begin_ = 0, auxiliary_variables_end_ = 0;  ///< [begin, end)
  int auxiliary_rows_begin_ = 0, auxiliary_rows_end_ = 0;
};

}  // namespace fesd
