#pragma once

#include <memory>
#include <vector>

#include "fesd_trajopt/discretization/butcher_tableau.h"
#include "fesd_trajopt/discretization/collocation_grid.h"
#include "fesd_trajopt/discretization/discretization.h"
#include "fesd_trajopt/function/smooth_function.h"

namespace fesd {

/// What the PDS and the Filippov discretisations share: the OCP, its options and Runge-Kutta
/// tableau, the NLP with its collocation grid (start state, controls, element lengths, stage and
/// end states), the Runge-Kutta rows, the boundaries where step equilibration acts, and guesses
/// that depend on the grid alone. A model's discretisation adds the algebraic variables (lifted
/// constraints, multipliers, auxiliaries) and their rows.
class CollocationDiscretization : public Discretization {
 public:
  // The NLP's active-set hook refers to this object: it stays where it was built.
  CollocationDiscretization(const CollocationDiscretization&) = delete;
  CollocationDiscretization& operator=(const CollocationDiscretization&) = delete;

  NlpAssembly& nlp() override { return nlp_; }
  const NlpAssembly& nlp() const override { return nlp_; }
  bool stepsAreFree() const override { return steps_free_; }
  void fixControl(int interval, const Eigen::VectorXd& u) override;
  /// Frees the control of interval k within the OCP's control bounds.
  void freeControl(int interval);
  /// A solution of the same kind of discretisation with the same grid sizes (e.g. the standard
  /// method's) as a guess: the grid's variables copied, the dependent ones completed.
  std::vector<double> adoptedGuess(const Discretization& other,
                                   const std::vector<double>& solution) const override;
  /// The trajectory's steps (clipped to the step bounds), stage and end states and controls;
  /// its pair values through guessPairValues.
  std::vector<double> guessFromTrajectory(const Trajectory& trajectory) const override;
  /// The grid's times, steps, states and controls, each element's complementarity-pair values
  /// and the switches between them; times start at start_time.
  Trajectory extract(const double* x, double start_time = 0.0,
                     double activity_tolerance = kDefaultActivityTolerance,
                     double penetration_tolerance = kDefaultPenetrationTolerance) const override;

  /// The modes' choice of zero sides; empty when the NLP has complementarity pairs that are no
  /// mode pairs (the big-M step equilibration's auxiliaries).
  std::vector<bool> activeSetOf(const PairModes& modes) const override;
  /// The pair alone takes the other mode (the constraints of a PDS are independent).
  void switchPair(PairModes& modes, int pair, int boundary, bool was_active) const override;

  std::vector<int> startAndControlVariables() const override;
  int finalStateIndex() const override { return grid_.end_states.back(); }
  std::vector<int> stepIndices() const override { return grid_.steps; }

  const OcpDefinition& ocp() const { return ocp_; }
  const DiscretizationOptions& options() const { return options_; }
  const ButcherTableau& tableau() const { return tableau_; }
  int numElements() const { return grid_.numElements(); }  ///< all intervals
  /// h0 of an element: its control interval's length over the interval's elements.
  double nominalStep(int element) const { return grid_.nominal_steps[element]; }
  /// Whether an element is the first of its control interval.
  bool startsInterval(int element) const { return grid_.startsInterval(element); }
  int startStateIndex() const { return start_state_; }
  int controlIndex(int interval) const { return grid_.controls[interval]; }
  int stepIndex(int element) const { return grid_.steps[element]; }
  int stateIndex(int element, int stage) const { return grid_.stage_states[element][stage]; }

 protected:
  /// The states one element adds: its stage states and its end state (the last stage's when
  /// the scheme has c_ns = 1).
  struct ElementStates {
    std::vector<int> stages;
    int end = -1;
  };

  /// Validates the OCP and options; the derived constructor decides steps_free_ and builds.
  CollocationDiscretization(OcpDefinition ocp, DiscretizationOptions options);

  /// The start state's variables; bounds and guess come from fixStartState.
  void addStartState();
  /// Fixes the start state to x0 (bounds and guess).
  void fixStartState(const Eigen::VectorXd& x0);
  /// n_x state variables within the OCP's state bounds.
  int addStateVariables();
  /// Per control interval its control (free within its bounds) and per element its length
  /// (within the step bounds when steps_free_, else fixed at h0) followed by the variables that
  /// `add_element` adds; then core_variables_ is the count so far.
  template <class AddElement>
  void buildGrid(AddElement add_element);
  /// x_{n,i} - x_{n,0} - h_n sum_j a_ij v_j = 0 for the element's stages and, when its end is no
  /// stage, x_n,end - x_{n,0} - h_n sum_j b_j v_j = 0, with v_j = velocity(x_{n,j}, u, block_j):
  /// block_j of `block_size` variables starts at stage_blocks[j] (multipliers or modes).
  void addRungeKuttaRows(int element, const std::shared_ptr<const SmoothFunction>& velocity,
                         const std::vector<int>& stage_blocks, int block_size);
  /// Adds the complementarity (left^T x)(right^T x) <= sigma of `pair` in `element` and records
  /// which side is its constraint side, for activeSetOf.
  void addPairComplementarity(int element, int pair, const LinearExpression& left,
                              const LinearExpression& right, bool left_is_constraint,
                              double left_weight = 1.0, double right_weight = 1.0);
  /// The first index of the state an element starts from.
  int elementStartState(int element) const;
  /// The elements whose boundary with the element before lies inside a control interval: there
  /// step equilibration acts (a control jump may switch at any boundary).
  std::vector<int> innerBoundaries() const;
  /// The row h_{n-1} - h_n, free until polishing fixes it at 0 at a boundary without switch.
  int addEqualStepsRow(int element);
  /// Throws std::invalid_argument unless `solution` has this NLP's size.
  void requireOwnSize(const std::vector<double>& solution, const char* caller) const;
  /// The number of complementarity pairs per stage point (constraints, or modes).
  virtual int numPairs() const = 0;
  /// Fills each element's pair matrices (and whatever else the model reads) from x.
  virtual void readPairValues(const double* x, Trajectory& trajectory) const = 0;
  /// Which pairs are active at the start of the solution x.
  virtual std::vector<bool> activeAtStart(const double* x, const Trajectory& trajectory,
                                          double tolerance) const = 0;
  /// Sets each stage point's pair variables (multipliers, lifted values, modes) of a guess whose
  /// grid variables come from `trajectory` (guessFromTrajectory).
  virtual void guessPairValues(const Trajectory& trajectory, std::vector<double>& x) const = 0;
  /// Sets the variables that follow from the grid's (lifted values, boundary multipliers,
  /// auxiliaries) consistently with them.
  virtual void completeDependentVariables(std::vector<double>& x) const = 0;

  OcpDefinition ocp_;
  DiscretizationOptions options_;
  ButcherTableau tableau_;
  int nx_ = 0, nu_ = 0;
  bool steps_free_ = false;
  NlpAssembly nlp_;
  int start_state_ = -1;
  CollocationGrid grid_;
  /// Start, controls, steps and element variables: the same in any method.
  int core_variables_ = 0;

 private:
  /// Where a complementarity pair of the NLP comes from, in the order of the NLP's pairs.
  struct PairOrigin {
    int element, pair;
    bool left_is_constraint;
  };
  std::vector<PairOrigin> pair_origins_;
};

template <class AddElement>
void CollocationDiscretization::buildGrid(AddElement add_element) {
  for (int k = 0; k < ocp_.num_intervals; ++k) {
    grid_.controls.push_back(
        nlp_.addVariables(nu_, -NlpAssembly::kInfinity, NlpAssembly::kInfinity));
    freeControl(k);
    for (int n = grid_.first_element[k]; n < grid_.first_element[k + 1]; ++n) {
      const double h0 = grid_.nominal_steps[n];
      const double lower = steps_free_ ? (1.0 - options_.step_bound) * h0 : h0;
      const double upper = steps_free_ ? (1.0 + options_.step_bound) * h0 : h0;
      grid_.steps.push_back(nlp_.addVariables(1, lower, upper, h0));
      const ElementStates states = add_element(grid_.numElements() - 1);
      grid_.stage_states.push_back(states.stages);
      grid_.end_states.push_back(states.end);
    }
  }
  core_variables_ = nlp_.numVariables();
}

}  // namespace fesd
