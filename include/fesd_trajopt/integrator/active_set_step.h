#pragma once

#include <string>
#include <vector>

#include "fesd_trajopt/discretization/discretization.h"
#include "fesd_trajopt/solver/mpcc_solver.h"
#include "fesd_trajopt/solver/square_newton.h"

namespace fesd {

/// How an active-set step ended.
enum class ActiveSetOutcome {
  kPredicted,  ///< the predicted modes held: no switch in the step
  kLocated,    ///< switches placed at element boundaries from the signs the prediction violated
  kFailed,     ///< no mode sequence tried satisfies every FESD condition: solve by homotopy
};

struct ActiveSetOptions {
  double tolerance = 1e-9;  ///< for signs, rows, bounds and complementarity
  int max_sequences = 4;    ///< mode sequences tried before giving up
  /// How the solution is read (Discretization::extract): the step's start time, tolerances.
  double start_time = 0.0;
  double activity_tolerance = kDefaultActivityTolerance;
  double penetration_tolerance = kDefaultPenetrationTolerance;
};

struct ActiveSetStep {
  ActiveSetOutcome outcome = ActiveSetOutcome::kFailed;
  MpccReport report;  ///< when solved: status success, polished, the solution
  Trajectory piece;   ///< when solved: the solution read with the options' times and tolerances
  PairModes modes;    ///< when solved: the modes its solution takes
  int newton_iterations = 0;
  int mode_sequences = 0;  ///< mode sequences tried
  std::string failure;     ///< why the last one was rejected
};

/// The modes a step starts with: those at the end of the previous step's last element (active
/// where the constraint side is zero and the multiplier positive), or, for the first step,
/// the pairs active at the start state.
PairModes predictModes(const Trajectory* previous, const std::vector<bool>& active_at_start,
                       int num_elements, double tolerance);

/// Solves one simulation step (start state and control already set in `discretization`) as the
/// smooth square system its active set leaves, by Newton's method, with modes constant over
/// the step as `predicted`; where the result violates a sign (c < 0 for an inactive pair,
/// lambda < 0 for an active one), the pair switches at the element boundary nearest to where
/// the sign changed, with the steps free (cross-complementarity), and the system is solved
/// again, up to `max_sequences` mode sequences. A solution is accepted only if it satisfies
/// every FESD condition (bounds, rows, complementarity and step equilibration at sigma = 0) to
/// `tolerance`: it is then the exact solution of the same equations the polished homotopy
/// solves.
///
/// Where the modes leave a boundary inside a control interval unswitched, its steps are equal
/// (equalStepTies), which the step equilibration may leave free. `newton` keeps its
/// factorisation's structure for the next step of the same active set.
ActiveSetStep solveByActiveSets(Discretization& discretization, const std::vector<double>& guess,
                                const PairModes& predicted, const ActiveSetOptions& options,
                                SquareNewton& newton);
/// The same with a Newton solver of its own.
ActiveSetStep solveByActiveSets(Discretization& discretization, const std::vector<double>& guess,
                                const PairModes& predicted, const ActiveSetOptions& options);

/// The steps of the elements on both sides of each boundary inside a control interval where no
/// pair changes its mode (Table I of Pozharskiy et al. 2024: no switch there, equal steps).
std::vector<VariableTie> equalStepTies(const Discretization& discretization,
                                       const PairModes& modes);

}  // namespace fesd
