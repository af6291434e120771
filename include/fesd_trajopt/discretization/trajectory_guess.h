#pragma once

#include <functional>
#include <vector>

#include <Eigen/Dense>

namespace fesd {

/// A guess of an OCP's solution as functions of time (e.g. a planned motion), for
/// Discretization::guessFrom.
struct TrajectoryGuess {
  std::function<Eigen::VectorXd(double)> state;  ///< x(t); required
  /// The PDS multipliers lambda(t), one per constraint; empty: 0. (Filippov models take their
  /// algebraic variables from the states' regions.)
  std::function<Eigen::VectorXd(double)> multipliers;
  std::vector<Eigen::VectorXd> controls;  ///< one per control interval; empty: 0
};

}  // namespace fesd
