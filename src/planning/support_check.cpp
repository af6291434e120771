// Whether a plan only pushes bodies into their supports (planning/support_check.h).
#include "fesd_trajopt/planning/support_check.h"

#include <algorithm>

namespace fesd {

std::vector<double> supportLifts(const SceneTask& task, const Trajectory& plan,
                                 const std::vector<ContactPair>& modelled) {
  const Scene& scene = task.scene;
  std::vector<double> lifts(scene.bodies().size(), 0.0);
  const SupportLiftRates lift = scene.supportLiftRates(modelled, scene.supportedBodies());
  if (!lift.rates) return lifts;
  const int nx = scene.stateSize(), nu = scene.controlSize();
  const int nc = static_cast<int>(modelled.size());
  // The rates do not depend on u: zeros in its place.
  Eigen::VectorXd input = Eigen::VectorXd::Zero(nx + nu + nc);
  Eigen::VectorXd rates(lift.bodies.size());
  for (const ElementValues& element : plan.elements) {
    const int stages = static_cast<int>(element.stage_states.cols());
    if (element.stage_multipliers.rows() != nc) continue;
    for (int j = 0; j < stages; ++j) {
      input.head(nx) = element.stage_states.col(j);
      input.tail(nc) = element.stage_multipliers.col(j);
      lift.rates->evaluate(input.data(), rates.data());
      for (size_t i = 0; i < lift.bodies.size(); ++i) {
        lifts[lift.bodies[i]] += element.step * std::max(0.0, rates(i)) / stages;
      }
    }
  }
  return lifts;
}

}  // namespace fesd
