#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/function/smooth_function.h"

namespace fesd {

/// A constraint becoming active (contact) or inactive (release) at an element boundary.
struct SwitchEvent {
  enum class Kind { kContact, kRelease };
  double time;
  int constraint;
  Kind kind;
  int element;  ///< global index of the first element after the switch

  static std::string kindName(Kind kind) { return kind == Kind::kContact ? "contact" : "release"; }
};

/// A switch that the element boundaries do not resolve. FESD places switches at element
/// boundaries; when an interval has more switches than its elements can hold, the solution
/// either changes a constraint's active set inside an element (the stage values show it apart,
/// c > lambda, at one stage and in contact, lambda > c, at another; also what the standard
/// method does at every switch) or steps over the contact altogether (the element's collocation
/// polynomial passes through the constraint, c < 0, between stage points that all satisfy it).
/// The second test is a heuristic with a depth tolerance; the first is exact.
/// Either way the solution is only low-order accurate there.
struct UnresolvedSwitch {
  int element;  ///< global element index
  int interval;
  int constraint;
  double start_time, end_time;  ///< the element's time span
  /// Whether the element steps over the contact (else: its active set changes inside it).
  bool passes_through;
};

/// One finite element of a solution: its stage values, in the order of the tableau's nodes.
struct ElementValues {
  int interval;
  double start_time;
  double step;                        ///< h_n
  Eigen::MatrixXd stage_states;       ///< n_x x n_s
  Eigen::MatrixXd stage_multipliers;  ///< lambda, n_c x n_s
  Eigen::MatrixXd stage_constraints;  ///< c(x) at the stage points, n_c x n_s
  /// Per constraint, the smallest signed distance along the element's collocation polynomial
  /// between its points (lowestConstraintBetweenStages); empty when not evaluated.
  Eigen::VectorXd lowest_constraints;
};

/// A discretised DCS trajectory: element boundaries, stage values, controls, switches.
struct Trajectory {
  std::vector<double> times;            ///< element boundary times (elements + 1)
  std::vector<Eigen::VectorXd> states;  ///< states at those times
  std::vector<ElementValues> elements;
  std::vector<Eigen::VectorXd> controls;  ///< one per control interval
  std::vector<double> interval_times;     ///< control interval boundaries (intervals + 1)
  std::vector<SwitchEvent> switches;
  std::vector<UnresolvedSwitch> unresolved_switches;
  /// The tableau's nodes c: where an element's stage points lie, as fractions of its length.
  Eigen::VectorXd stage_nodes;

  bool switchesResolved() const { return unresolved_switches.empty(); }
  const Eigen::VectorXd& finalState() const { return states.back(); }
  /// Concatenates a trajectory that starts where this one ends. Switches are cleared: their
  /// classification depends on the whole history, so call classifySwitches() on the result.
  void append(const Trajectory& next);
};

/// Threshold below which both sides of a complementarity pair count as zero.
constexpr double kDefaultActivityTolerance = 1e-6;

/// Reads contact and release events from the element values: an element is in contact with
/// constraint k when its stage multipliers outweigh its stage constraint values; elements where
/// both are negligible (weakly active) keep the previous classification. `initially_active[k]`
/// classifies the start point. Events are placed at element boundaries.
std::vector<SwitchEvent> detectSwitches(const std::vector<ElementValues>& elements,
                                        const std::vector<bool>& initially_active,
                                        double activity_tolerance = kDefaultActivityTolerance);

/// The smallest signed distance c / |grad c| (in state units, to first order) of each constraint
/// along an element's collocation polynomial: the polynomial of degree n_s through the start
/// state at node 0 and the stage states at `nodes` (the tableau's c), sampled at
/// `samples_per_gap` points between consecutive nodes.
Eigen::VectorXd lowestConstraintBetweenStages(const SmoothFunction& constraints,
                                              const Eigen::VectorXd& nodes,
                                              const Eigen::VectorXd& start_state,
                                              const Eigen::MatrixXd& stage_states,
                                              int samples_per_gap = 4);

/// The smallest signed distance of constraint `constraint` along an element's collocation
/// polynomial and where it is (the fraction of the element), as lowestConstraintBetweenStages
/// samples it, then located to rounding by a golden-section search between the neighbours of
/// its lowest sample: whether a polynomial only touches a boundary (a grazing contact) is a
/// question of a few ulps.
struct ClosestApproach {
  double distance;
  double fraction;
};
ClosestApproach closestApproach(const SmoothFunction& constraints, int constraint,
                                const Eigen::VectorXd& nodes, const Eigen::VectorXd& start_state,
                                const Eigen::MatrixXd& stage_states, int samples_per_gap = 4);

/// The weights of the start state and of each stage state in an element's collocation polynomial
/// at the fraction `t` of the element (the Lagrange basis at nodes 0 and `nodes`, evaluated at t).
std::vector<double> collocationWeights(const Eigen::VectorXd& nodes, double t);

/// The state of an element's collocation polynomial, the polynomial of degree n_s through the
/// start state at 0 and the stage states at `nodes`, at the fraction `t` of the element.
Eigen::VectorXd collocationState(const Eigen::VectorXd& nodes, const Eigen::VectorXd& start_state,
                                 const Eigen::MatrixXd& stage_states, double t);

/// A trajectory's states in time order, for checks between element boundaries: its start, then
/// per element between consecutive stage nodes `samples_per_gap` points of its collocation
/// polynomial and the stage state, and its end state if that is no stage (c_ns < 1).
std::vector<Eigen::VectorXd> densePath(const Trajectory& trajectory, int samples_per_gap = 4);

/// Depth (state units) to which an element's collocation polynomial may pass through a
/// constraint before the element counts as stepping over a contact. Within resolved contacts
/// the polynomial bends off the constraint by the interpolation error only (measured: at most
/// 9e-3 on the showcase OCP with N = 20, 40 and 2, 3 elements); a skipped contact goes deep
/// (0.09 on Pozharskiy et al. 2024 Example 1 in one element).
constexpr double kDefaultPenetrationTolerance = 3e-2;

/// The elements with an unresolved switch (see UnresolvedSwitch): an active set that changes
/// between stages (stages where both c and lambda are at most `activity_tolerance` count as
/// either side), or lowest_constraints below -penetration_tolerance.
std::vector<UnresolvedSwitch> findUnresolvedSwitches(
    const std::vector<ElementValues>& elements,
    double activity_tolerance = kDefaultActivityTolerance,
    double penetration_tolerance = kDefaultPenetrationTolerance);

/// Sets a trajectory's switches (detectSwitches) and unresolved switches
/// (findUnresolvedSwitches) from its element values; `initially_active` classifies its start.
void classifySwitches(Trajectory& trajectory, const std::vector<bool>& initially_active,
                      double activity_tolerance = kDefaultActivityTolerance,
                      double penetration_tolerance = kDefaultPenetrationTolerance);

/// A sentence for a result's message: how many elements hold an unresolved switch and the first
/// one; "" when there are none.
std::string describeUnresolvedSwitches(const std::vector<UnresolvedSwitch>& unresolved);

}  // namespace fesd
