#include "fesd_trajopt/model/dcs_model.h"

#include <algorithm>
#include <stdexcept>

namespace fesd {

DcsModel::DcsModel(int state_size, int control_size, int constraint_size,
                   std::shared_ptr<const SmoothFunction> velocity,
                   std::shared_ptr<const SmoothFunction> constraints, std::string name,
                   Eigen::VectorXd constraint_scales)
    : state_size_(state_size),
      control_size_(control_size),
      constraint_size_(constraint_size),
      velocity_(std::move(velocity)),
      constraints_(std::move(constraints)),
      name_(std::move(name)),
      constraint_scales_(constraint_scales.size() ? std::move(constraint_scales)
                                                  : Eigen::VectorXd(Eigen::VectorXd::Ones(
                                                        std::max(constraint_size, 0)))) {
  if (state_size_ < 1 || control_size_ < 0 || constraint_size_ < 0) {
    throw std::invalid_argument("DcsModel: invalid dimensions");
  }
  if (!velocity_ || velocity_->inputSize() != state_size_ + control_size_ + constraint_size_ ||
      velocity_->outputSize() != state_size_) {
    throw std::invalid_argument("DcsModel '" + name_ +
                                "': velocity must map (x, u, lambda) to R^n_x");
  }
  if (!constraints_ || constraints_->inputSize() != state_size_ ||
      constraints_->outputSize() != constraint_size_) {
    throw std::invalid_argument("DcsModel '" + name_ + "': constraints must map x to R^n_c");
  }
  if (constraint_scales_.size() != constraint_size_ || !(constraint_scales_.array() > 0.0).all()) {
    throw std::invalid_argument("DcsModel '" + name_ + "': one positive scale per constraint");
  }
}

}  // namespace fesd
