#include "fesd_trajopt/model/stewart_model.h"

#include <algorithm>
#include <limits>
#include <stdexcept>

namespace fesd {

StewartModel::StewartModel(int state_size, int control_size, std::vector<int> modes_per_subsystem,
                           std::shared_ptr<const SmoothFunction> velocity,
                           std::shared_ptr<const SmoothFunction> indicators, std::string name)
    : state_size_(state_size),
      control_size_(control_size),
      modes_per_subsystem_(std::move(modes_per_subsystem)),
      velocity_(std::move(velocity)),
      indicators_(std::move(indicators)),
      name_(std::move(name)) {
  if (state_size_ < 1 || control_size_ < 0 || modes_per_subsystem_.empty()) {
    throw std::invalid_argument("StewartModel: invalid dimensions");
  }
  for (int k = 0; k < numSubsystems(); ++k) {
    if (modes_per_subsystem_[k] < 1) {
      throw std::invalid_argument("StewartModel: every subsystem needs a mode");
    }
    subsystem_of_mode_.insert(subsystem_of_mode_.end(), modes_per_subsystem_[k], k);
  }
  if (!velocity_ || velocity_->inputSize() != state_size_ + control_size_ + numModes() ||
      velocity_->outputSize() != state_size_) {
    throw std::invalid_argument("StewartModel '" + name_ +
                                "': velocity must map (x, u, theta) to R^n_x");
  }
  if (!indicators_ || indicators_->inputSize() != state_size_ ||
      indicators_->outputSize() != numModes()) {
    throw std::invalid_argument("StewartModel '" + name_ + "': indicators must map x to R^n_f");
  }
}

void StewartModel::lpMultipliers(const double* x, double* lambda, double* mu) const {
  indicators_->evaluate(x, lambda);
  std::fill(mu, mu + numSubsystems(), std::numeric_limits<double>::infinity());
  for (int i = 0; i < numModes(); ++i) mu[subsystemOf(i)] = std::min(mu[subsystemOf(i)], lambda[i]);
  for (int i = 0; i < numModes(); ++i) lambda[i] -= mu[subsystemOf(i)];
}

Eigen::MatrixXd signMatrix(int switching_functions) {
  if (switching_functions < 1 || switching_functions > 16) {
    throw std::invalid_argument("signMatrix: 1..16 switching functions");
  }
  const int m = switching_functions;
  Eigen::MatrixXd sign(1 << m, m);
  for (int i = 0; i < sign.rows(); ++i) {
    for (int j = 0; j < m; ++j) sign(i, j) = (i >> (m - 1 - j)) & 1 ? -1.0 : 1.0;
  }
  return sign;
}

}  // namespace fesd
