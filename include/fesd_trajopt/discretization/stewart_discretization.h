#pragma once

#include <memory>
#include <vector>

#include "fesd_trajopt/discretization/collocation_discretization.h"
#include "fesd_trajopt/discretization/step_equilibration_residual.h"
#include "fesd_trajopt/model/stewart_model.h"

namespace fesd {

/// The FESD (or, with switch detection off, the standard fixed-step) discretisation of an
/// OcpDefinition on a Filippov system in Stewart's form (Nurkanovic et al. 2024, Sec. 3) as a
/// relaxable MPCC:
///  - collocation equations of every finite element for xdot = F(x, u) theta (eq. 25), and for
///    a scheme with c_ns != 1 (Gauss-Legendre) the element's end state x_n + h sum_i b_i v_i,
///  - at every stage point g(x) - lambda - mu e = 0 and e^T theta^k = 1 per subsystem,
///  - standard method: theta _|_ lambda at every stage point,
///  - FESD: free steps summing to each control interval's length; (lambda, mu) at element
///    boundaries (eq. 27: the last stage's for Radau-IIA; for c_ns != 1 a boundary point with
///    g(x_n) - lambda - mu e = 0, lambda >= 0, Sec. 3.2.5 / 4.2.1, at every boundary including
///    the last; the start's likewise);
///    cross-complementarity (eq. 28/29) between an element's stage theta and every lambda of
///    its closure; step equilibration (eq. 31) |((h_n - h_{n-1}) / h0) eta_n| <= sigma relaxed
///    with the complementarity, with the indicator eta_n or tanh(eta_n),
///  - costs by the RK quadrature, control/state bounds, path and terminal constraints.
/// In the complementarity-pair terms of a Trajectory, theta plays the multiplier and lambda
/// the constraint value: mode i is active in an element when its theta_i outweighs lambda_i.
class StewartDiscretization : public CollocationDiscretization {
 public:
  StewartDiscretization(OcpDefinition ocp, DiscretizationOptions options);

  const StewartModel& model() const { return *model_; }

  void setInitialState(const Eigen::VectorXd& x0) override;
  /// Frees the start state within the OCP's initial state bounds again (a free-start OCP).
  void releaseInitialState();
  /// Nothing to take over: lambda at the start follows from the start state (eq. 39).
  void continueFrom(const Trajectory& previous, bool same_dynamics) override {}

  std::vector<double> constantGuess(
      const std::vector<Eigen::VectorXd>& controls = {}) const override;
  /// The guess's states and controls on the nominal grid, the modes of those states; its
  /// multipliers are not used.
  std::vector<double> guessFrom(const TrajectoryGuess& guess) const override;
  std::vector<double> translatedGuess(const std::vector<double>& previous_solution) const override;

  /// A mode that becomes active crosses over: the modes active in its subsystem at the boundary
  /// leave (a crossing, not sliding, which the homotopy finds if this fails).
  /// The mode's subsystem.
  int switchingGroup(int pair) const override { return model_->subsystemOf(pair); }
  void switchPair(PairModes& modes, int pair, int boundary, bool was_active) const override;
  /// Modes whose indicator is within tolerance of its subsystem's minimum.
  std::vector<bool> activeAt(const Eigen::VectorXd& x, double tolerance) const override;

  /// The switch indicator eta_n (eq. 31, without tanh) at every element boundary inside a
  /// control interval, in order; empty without step equilibration.
  std::vector<double> switchIndicators(const double* x) const;

 private:
  struct StagePoint {
    int x = -1, theta = -1, lambda = -1, mu = -1;  ///< first indices
  };
  /// (lambda, mu) of Stewart's LP at an element boundary state.
  struct BoundaryPoint {
    int lambda = -1, mu = -1;
  };
  struct Element {
    std::vector<StagePoint> stages;
    int start_state = -1, end_state = -1;
    BoundaryPoint start;  ///< FESD only
  };
  /// The step equilibration of the boundary between two elements of a control interval.
  struct Equilibration {
    int element;              ///< the later element of the boundary
    std::vector<int> inputs;  ///< h_{n-1}, h_n, then the indicator's blocks
    SwitchIndicator indicator;
    int relaxed_row, equal_steps_row;
  };

  void buildVariables();
  void buildBoundaryPoints();
  /// (lambda, mu) at a state with lambda = g(x) - mu e >= 0 (eq. 33/39); the
  /// cross-complementarity then pins mu to min g.
  BoundaryPoint addBoundaryPoint(int state);
  void buildDynamics();
  void buildAlgebraicRows(int state, int theta, int lambda, int mu, bool with_theta);
  void buildComplementarity();
  void buildStepEquilibration();
  /// With the active set fixed (polishing): the relaxed equilibration rows are dropped, and
  /// h_{n-1} = h_n imposed where eta_n cannot vanish (no switch, Nurkanovic et al. 2024
  /// Sec. 3.2.3).
  void equilibrateActiveSet();
  /// The lambda blocks of an element's closure: start boundary, stages, end boundary.
  std::vector<int> closureLambdas(int element) const;
  /// Sets (lambda, mu) to the LP multipliers at the state x[state].
  void setLpMultipliers(std::vector<double>& x, int state, int lambda, int mu) const;
  /// (lambda, mu) of every boundary point from its state.
  void completeDependentVariables(std::vector<double>& x) const override;
  int numPairs() const override { return nf_; }
  /// theta (the multiplier side) and lambda (the constraint side) at the stages.
  void readPairValues(const double* x, Trajectory& trajectory) const override;
  /// The modes active at the start state (activeAt).
  std::vector<bool> activeAtStart(const double* x, const Trajectory& trajectory,
                                  double tolerance) const override;
  /// lambda, mu of the LP at the point's state, and theta on each subsystem's (first) mode
  /// of smallest indicator.
  void setModeOfState(std::vector<double>& x, const StagePoint& point) const;
  /// setModeOfState at every stage point.
  void setModesOfStates(std::vector<double>& x) const;
  /// The modes of the guess's states (the trajectory's own algebraic values are not needed).
  void guessPairValues(const Trajectory& trajectory, std::vector<double>& x) const override;

  std::shared_ptr<const StewartModel> model_;
  int nf_, nsys_;
  bool stage_at_end_;  ///< c_ns = 1 (Radau-IIA): the last stage is the element's end
  std::vector<Element> elements_;
  BoundaryPoint final_boundary_;  ///< at the last element's end, c_ns != 1 only
  std::vector<Equilibration> equilibration_;
};

}  // namespace fesd
