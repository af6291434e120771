#include "support/bead_model.h"

#include "fesd_trajopt/model/autodiff_model.h"

namespace fesd_test {

std::shared_ptr<const fesd::DcsModel> beadModel() {
  return std::make_shared<fesd::DcsModel>(
      fesd::makeAutoDiffModel(3, 2, 2, BeadDynamics{}, BeadConstraints{}, "bead"));
}

}  // namespace fesd_test
