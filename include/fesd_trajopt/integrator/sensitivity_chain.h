#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/discretization/trajectory.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/integrator/step_sensitivity.h"

namespace fesd {

/// Chains the sensitivities of a simulation's parts into those of the whole run by the chain
/// rule: each part's derivatives by its own start state and control, times the derivatives of
/// that start by (x0, u_0 .. u_{N-1}). Also the time of every element boundary, as the sum of the
/// part's element lengths before it (the part's start time is fixed).
class SensitivityChain {
 public:
  SensitivityChain(int state_size, int control_size, int num_steps);

  /// The next part of the trajectory, in step `step`, with `elements` elements.
  void addPart(const StepSensitivity& part, int step, int elements);
  /// From here on nothing is defined, for `reason`.
  void stopDefining(const std::string& reason);
  /// A step's end: its states' derivatives are the chain so far.
  void endStep();
  bool defined() const { return why_undefined_.empty(); }
  /// The result, with the derivatives of the times of `switches` (at element boundaries).
  SimulationSensitivities finish(const std::vector<SwitchEvent>& switches) const;

 private:
  int nx_, nu_;
  Eigen::MatrixXd chain_;  ///< d x / d (x0, u_0 .. u_{N-1}) at the end of the parts so far
  std::vector<Eigen::RowVectorXd> boundary_times_;  ///< per element boundary so far
  std::vector<Eigen::MatrixXd> states_;
  int defined_steps_ = 0;
  std::string why_undefined_;
};

}  // namespace fesd
