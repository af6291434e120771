#include "fesd_trajopt/integrator/sensitivity_chain.h"

#include <limits>

namespace fesd {
namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace

SensitivityChain::SensitivityChain(int state_size, int control_size, int num_steps)
    : nx_(state_size),
      nu_(control_size),
      chain_(Eigen::MatrixXd::Zero(state_size, state_size + num_steps * control_size)),
      boundary_times_(1, Eigen::RowVectorXd::Zero(chain_.cols())) {
  chain_.leftCols(nx_).setIdentity();
}

void SensitivityChain::stopDefining(const std::string& reason) {
  if (defined()) why_undefined_ = reason;
}

void SensitivityChain::addPart(const StepSensitivity& part, int step, int elements) {
  if (defined() && !part.defined)
    stopDefining("step " + std::to_string(step) + ": " + part.why_undefined);
  if (!defined()) {
    boundary_times_.insert(boundary_times_.end(), elements,
                           Eigen::RowVectorXd::Constant(chain_.cols(), kNaN));
    return;
  }
  const Eigen::MatrixXd start = chain_;
  const auto by_start = [&](const Eigen::MatrixXd& derivatives) {
    Eigen::MatrixXd chained = derivatives.leftCols(nx_) * start;
    chained.middleCols(nx_ + step * nu_, nu_) += derivatives.rightCols(nu_);
    return chained;
  };
  chain_ = by_start(part.final_state);
  const Eigen::MatrixXd steps = by_start(part.steps);
  Eigen::RowVectorXd time = Eigen::RowVectorXd::Zero(chain_.cols());
  for (int e = 0; e < elements; ++e) {
    time += steps.row(e);
    boundary_times_.push_back(time);
  }
}

void SensitivityChain::endStep() {
  states_.push_back(defined() ? chain_ : Eigen::MatrixXd::Constant(nx_, chain_.cols(), kNaN));
  defined_steps_ += defined();
}

SimulationSensitivities SensitivityChain::finish(const std::vector<SwitchEvent>& switches) const {
  SimulationSensitivities result;
  result.states = states_;
  result.defined_steps = defined_steps_;
  result.why_undefined = why_undefined_;
  // Every switch sits on an element boundary (one inside an element is an unresolved switch).
  for (const SwitchEvent& event : switches) {
    result.switch_times.push_back(boundary_times_.at(event.element));
  }
  return result;
}

}  // namespace fesd
