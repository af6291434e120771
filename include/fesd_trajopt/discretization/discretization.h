#pragma once

#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/discretization/discretization_options.h"
#include "fesd_trajopt/discretization/trajectory.h"
#include "fesd_trajopt/discretization/trajectory_guess.h"
#include "fesd_trajopt/model/ocp_definition.h"
#include "fesd_trajopt/nlp/nlp_assembly.h"

namespace fesd {

/// Per element and complementarity pair (constraint k of a PDS, mode i of a Filippov system),
/// whether the pair is active there: its constraint side (c, or Stewart's lambda) zero and its
/// multiplier side (lambda, or theta) free; inactive: the multiplier side zero.
using PairModes = std::vector<std::vector<bool>>;

/// A discretisation of an OcpDefinition as a relaxable MPCC, as the integrator and the OCP
/// solver use it, whatever the model kind: the NLP, guesses, and reading the solution.
class Discretization {
 public:
  virtual ~Discretization() = default;

  virtual NlpAssembly& nlp() = 0;
  virtual const NlpAssembly& nlp() const = 0;
  /// True when element lengths are free (FESD on and something can switch).
  virtual bool stepsAreFree() const = 0;

  /// Fixes the start state.
  virtual void setInitialState(const Eigen::VectorXd& x0) = 0;
  /// Takes over what the next simulation step needs from the end of the previous one.
  /// `same_dynamics`: the right-hand side continues unchanged into this step (same control), so
  /// a contact force cannot jump down at its start (Pozharskiy et al. 2024, Proposition 2).
  virtual void continueFrom(const Trajectory& previous, bool same_dynamics) = 0;
  /// Fixes the control of interval k to u (simulation).
  virtual void fixControl(int interval, const Eigen::VectorXd& u) = 0;

  /// Every state at the start state, nominal steps, the given controls (clipped to their
  /// bounds; empty means 0), algebraic variables consistent with the start state.
  virtual std::vector<double> constantGuess(
      const std::vector<Eigen::VectorXd>& controls = {}) const = 0;
  /// A previous, equally structured solution moved to the current start state.
  virtual std::vector<double> translatedGuess(
      const std::vector<double>& previous_solution) const = 0;
  /// The guess's states, multipliers and controls (clipped to their bounds) at the stage points
  /// of the nominal grid; the rest consistent with them.
  virtual std::vector<double> guessFrom(const TrajectoryGuess& guess) const = 0;
  /// A trajectory of this discretisation's model on a grid of the same sizes (intervals,
  /// elements per interval, stages), e.g. a solution of a problem with fewer constraints moved
  /// into this one's coordinates: its steps, states, controls and multipliers (clipped to their
  /// bounds); the rest consistent with them.
  virtual std::vector<double> guessFromTrajectory(const Trajectory& trajectory) const = 0;
  /// A solution of a discretisation of the same OCP on the same grid (e.g. the standard
  /// method's) as a guess for this one.
  virtual std::vector<double> adoptedGuess(const Discretization& other,
                                           const std::vector<double>& solution) const = 0;

  /// Reads the trajectory (times, states, stage values, controls, switches, unresolved switches)
  /// from a solution.
  virtual Trajectory extract(const double* x, double start_time = 0.0,
                             double activity_tolerance = kDefaultActivityTolerance,
                             double penetration_tolerance = kDefaultPenetrationTolerance) const = 0;
  /// The choice of zero sides (RelaxedMpcc::fixGivenActiveSet) that imposes `modes`: switches
  /// only where the modes change between elements, at that boundary. Empty when the NLP has
  /// pairs the modes do not decide.
  virtual std::vector<bool> activeSetOf(const PairModes& modes) const = 0;
  /// The variables of zero sides that the active set of `modes` leaves free: a pair's force at
  /// the end of an element where it lets go at the boundary at which another pair's contact
  /// begins. The contact makes that force jump to zero, which the cross-complementarity (derived
  /// for forces that fall continuously) forbids. Empty where the model has no such forces.
  virtual std::vector<int> jumpingForces(const PairModes& modes) const { return {}; }
  /// Switches `pair`, found violating its signs in mode `was_active`, to the other mode from
  /// element `boundary` on, with whatever else that switch implies for the other pairs.
  virtual void switchPair(PairModes& modes, int pair, int boundary, bool was_active) const = 0;
  /// What the sensitivities of a simulation step (one control interval) differentiate by: the
  /// variables setInitialState and fixControl(0, u) fix, x0's then u's. Data the model derives
  /// from them (a PDS's c(x0)) enter no equation of a step's active-set system, only its
  /// decisions.
  virtual std::vector<int> startAndControlVariables() const = 0;
  /// The first index of the state at the last element's end.
  virtual int finalStateIndex() const = 0;
  /// Each element's length, in order.
  virtual std::vector<int> stepIndices() const = 0;
  /// Whether `pair` comes within `tolerance` of its boundary inside `element` of `piece` (a
  /// solution of this discretisation) without touching it at a stage point: a grazing contact,
  /// which stage values alone do not show. False where the model has no such geometry.
  virtual bool grazesBetweenStages(const Trajectory& piece, int element, int pair,
                                   double tolerance) const {
    return false;
  }
  /// Pairs of one group switch together as one event (a Filippov subsystem's modes: one leaves
  /// as another enters); pairs of different groups are independent constraints.
  virtual int switchingGroup(int pair) const { return pair; }
  /// Whether a release leaves the flow continuously differentiable: no jump of the velocity
  /// there, so no saltation (a PDS: its force falls continuously to zero).
  virtual bool releasesAreSmooth() const { return false; }
  /// Which complementarity pairs are active at a state (the classification of a trajectory's
  /// start for detectSwitches).
  virtual std::vector<bool> activeAt(const Eigen::VectorXd& x, double tolerance) const = 0;
};

/// The discretisation of `ocp` that its model builds.
std::unique_ptr<Discretization> discretize(const OcpDefinition& ocp,
                                           const DiscretizationOptions& options);

}  // namespace fesd
