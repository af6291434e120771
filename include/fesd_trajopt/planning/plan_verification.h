#pragma once

#include <limits>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/discretization/trajectory.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// A contact that the plan does not hold: the plan passes a pair by in a control interval (no
/// force of that pair in it) where the fine re-simulation of that interval touches it, or where
/// the plan's own collocation polynomials cut into it between stage points.
struct Graze {
  ContactPair pair;  ///< the full task's indices
  int interval = 0;
  double time = 0.0;  ///< of the touch: the fine contact's start, else the plan's deepest point
  /// The plan's smallest gap of the pair along its collocation polynomials in that interval
  /// (scene units; negative: the plan cuts through the body between stage points).
  double depth = 0.0;
  int element = -1;       ///< the plan's element of that smallest gap
  double fraction = 0.0;  ///< where in it, as a fraction of its length
  bool touched = false;   ///< the fine re-simulation makes the contact
};

/// The verification of a plan: its controls re-simulated on a finer grid with every pair in
/// reach, interval by interval from the plan's own states (multiple shooting: the error the
/// discretisation makes, which finer grids lower) and from its start in one run (open loop:
/// what executing the controls without feedback gives, which an unstable push amplifies).
struct Verification {
  SolveStatus status = SolveStatus::kSolverError;
  std::string message;  ///< why it failed; "" on success
  /// The largest distance of an interval's re-simulated end from the plan's state there;
  /// infinity when a re-simulation failed.
  double error = std::numeric_limits<double>::infinity();
  std::vector<double> interval_errors;  ///< per control interval
  /// The open-loop re-simulation's end state's distance from the plan's; infinity when it failed.
  double open_loop_error = std::numeric_limits<double>::infinity();
  /// The largest norm of d x(T) / d x(t_k) over the interval starts t_k along the plan (exact
  /// sensitivities of the fine re-simulation across switches): how much a deviation at t_k grows
  /// by the end when executed open loop. NaN when no interval's derivatives are defined.
  double open_loop_gain = std::numeric_limits<double>::quiet_NaN();
  /// Why the gain leaves out intervals (from the first one whose derivatives are undefined on,
  /// counted back from the end); "" when all are in.
  std::string gain_note;
  Trajectory open_loop;                      ///< of the full scene
  std::vector<ContactPair> open_loop_pairs;  ///< the pairs of its multipliers' rows
  /// The smallest gap of every pair in reach at the element boundaries of the interval
  /// re-simulations (negative: penetration).
  double gap = std::numeric_limits<double>::quiet_NaN();
  double relative_gap = std::numeric_limits<double>::quiet_NaN();  ///< the same over pairSize
  std::vector<Graze> grazes;                                       ///< in time order
  int modelled_pairs = 0;                                          ///< in the last re-simulation
  double seconds = 0.0;
};

/// The start state of each control interval of a trajectory (its element boundary), and its
/// end state last: intervals + 1 states.
std::vector<Eigen::VectorXd> intervalBoundaryStates(const Trajectory& trajectory);

/// Verifies a plan (the trajectory and pair decisions of an outcome of `task`) on the grid of
/// `fine`: multiple shooting with sensitivities, then the open-loop run, each lazily as the solve
/// (the modelled pairs first, then again with every checked pair that came within `margin`,
/// relative to pairSize, of contact until none does). The plan's grazes: pairs in reach that
/// the plan holds no force of in an interval where the interval's re-simulation touches them,
/// or where the plan's polynomials come closer than `graze_depth` (cut into the body).
Verification verifyPlan(const SceneTask& task, const Trajectory& plan,
                        const std::vector<PairDecision>& decisions, const SimulationOptions& fine,
                        double margin, double graze_depth);

/// The plan's own grazes: per modelled pair (decisions' modelled, in order: the plan's
/// multiplier rows) and control interval without a force of that pair, its smallest gap along
/// the collocation polynomials if below `depth` (a cut into the body between stage points).
std::vector<Graze> planGrazes(const SceneTask& task, const Trajectory& plan,
                              const std::vector<ContactPair>& modelled, double depth);

/// A sentence for an answer: the grazes, the first few named; "" when there are none.
std::string describeGrazes(const Scene& scene, const std::vector<Graze>& grazes);

}  // namespace fesd
