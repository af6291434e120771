#include "fesd_trajopt/core/dcs_model.h"

#include <stdexcept>

#include "fesd_trajopt/core/fesd_discretization.h"

namespace fesd {

DcsModel::DcsModel(int state_size, int control_size, int constraint_size,
                   std::shared_ptr<const SmoothFunction> velocity,
                   std::shared_ptr<const SmoothFunction> constraints, std::string name)
    : state_size_(state_size),
      control_size_(control_size),
      constraint_size_(constraint_size),
      velocity_(std::move(velocity)),
      constraints_(std::move(constraints)),
      name_(std::move(name)) {
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
}

std::unique_ptr<Discretization> DcsModel::discretize(const OcpDefinition& ocp,
                                                     const DiscretizationOptions& options) const {
  return std::make_unique<FesdDiscretization>(ocp, options);
}

}  // namespace fesd
