#include "fesd_trajopt/discretization/discretization.h"

#include <stdexcept>

namespace fesd {

std::unique_ptr<Discretization> discretize(const OcpDefinition& ocp,
                                           const DiscretizationOptions& options) {
  if (!ocp.model) throw std::invalid_argument("OcpDefinition: no model");
  return ocp.model->discretize(ocp, options);
}

}  // namespace fesd
