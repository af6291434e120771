#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

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

/// One finite element of a solution: its stage values, in the order of the tableau's nodes.
struct ElementValues {
  int interval;
  double start_time;
  double step;                        ///< h_n
  Eigen::MatrixXd stage_states;       ///< n_x x n_s
  Eigen::MatrixXd stage_multipliers;  ///< lambda, n_c x n_s
  Eigen::MatrixXd stage_constraints;  ///< c(x) at the stage points, n_c x n_s
};

/// A discretised DCS trajectory: element boundaries, stage values, controls, switches.
struct Trajectory {
  std::vector<double> times;            ///< element boundary times (elements + 1)
  std::vector<Eigen::VectorXd> states;  ///< states at those times
  std::vector<ElementValues> elements;
  std::vector<Eigen::VectorXd> controls;  ///< one per control interval
  std::vector<double> interval_times;     ///< control interval boundaries (intervals + 1)
  std::vector<SwitchEvent> switches;

  const Eigen::VectorXd& finalState() const { return states.back(); }
  /// Concatenates a trajectory that starts where this one ends. Switches are cleared: their
  /// classification depends on the whole history, so call detectSwitches() on the result.
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

}  // namespace fesd
