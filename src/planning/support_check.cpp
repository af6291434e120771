// Whether a plan only pushes bodies into their supports (planning/support_check.h).
#include "fesd_trajopt/planning/support_check.h"

#include <algorithm>
#include <memory>

namespace fesd {

std::vector<double> supportLifts(const SceneTask& task, const Trajectory& plan,
                                 const std::vector<ContactPair>& modelled) {
  const Scene& scene = task.scene;
  const int bodies = static_cast<int>(scene.bodies().size());
  std::vector<double> lifts(bodies, 0.0);
  // Per state coordinate: the supported body whose height it is and the support's normal's z.
  std::vector<int> body_of(scene.stateSize(), -1);
  std::vector<double> normal_z(bodies, 0.0);
  bool any = false;
  for (int b = 0; b < bodies; ++b) {
    const int support = scene.supportOf(b);
    if (support < 0) continue;
    body_of[scene.stateIndex(b) + 2] = b;
    normal_z[b] = scene.walls()[support].normal(2);
    any = true;
  }
  if (!any || modelled.empty()) return lifts;
  // The constraints' gradients are the forces' directions; the velocity masks the held part.
  const std::shared_ptr<const DcsModel> model = scene.model(modelled);
  const SmoothFunction& constraints = *model->constraints();
  const SparsityPattern& pattern = constraints.jacobianPattern();
  std::vector<double> values(pattern.nonzeros());
  std::vector<double> speed(bodies);
  for (const ElementValues& element : plan.elements) {
    const int stages = static_cast<int>(element.stage_states.cols());
    if (element.stage_multipliers.rows() != static_cast<int>(modelled.size())) continue;
    std::vector<double> mean(bodies, 0.0);
    for (int j = 0; j < stages; ++j) {
      const Eigen::VectorXd x = element.stage_states.col(j);
      constraints.evaluateJacobian(x.data(), values.data());
      std::fill(speed.begin(), speed.end(), 0.0);
      for (int e = 0; e < pattern.nonzeros(); ++e) {
        const int b = body_of[pattern.cols[e]];
        if (b >= 0) speed[b] += element.stage_multipliers(pattern.rows[e], j) * values[e];
      }
      for (int b = 0; b < bodies; ++b) {
        mean[b] += std::max(0.0, normal_z[b] * speed[b]) / stages;
      }
    }
    for (int b = 0; b < bodies; ++b) lifts[b] += element.step * mean[b];
  }
  return lifts;
}

}  // namespace fesd
