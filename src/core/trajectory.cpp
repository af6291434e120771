#include "fesd_trajopt/core/trajectory.h"

#include <algorithm>

namespace fesd {

void Trajectory::append(const Trajectory& next) {
  if (times.empty()) {
    *this = next;
    return;
  }
  times.insert(times.end(), next.times.begin() + 1, next.times.end());
  states.insert(states.end(), next.states.begin() + 1, next.states.end());
  elements.insert(elements.end(), next.elements.begin(), next.elements.end());
  controls.insert(controls.end(), next.controls.begin(), next.controls.end());
  interval_times.insert(interval_times.end(), next.interval_times.begin() + 1,
                        next.interval_times.end());
  switches.clear();  // classification depends on the whole history: detectSwitches() again
}

std::vector<SwitchEvent> detectSwitches(const std::vector<ElementValues>& elements,
                                        const std::vector<bool>& initially_active,
                                        double activity_tolerance) {
  std::vector<SwitchEvent> events;
  std::vector<bool> active = initially_active;
  for (size_t e = 0; e < elements.size(); ++e) {
    const ElementValues& element = elements[e];
    for (int k = 0; k < static_cast<int>(active.size()); ++k) {
      const double multiplier_sum = element.stage_multipliers.row(k).sum();
      const double constraint_sum = element.stage_constraints.row(k).cwiseMax(0.0).sum();
      if (std::max(multiplier_sum, constraint_sum) <= activity_tolerance) continue;
      const bool now_active = multiplier_sum > constraint_sum;
      if (now_active != active[k]) {
        events.push_back({element.start_time, k,
                          now_active ? SwitchEvent::Kind::kContact : SwitchEvent::Kind::kRelease,
                          static_cast<int>(e)});
        active[k] = now_active;
      }
    }
  }
  return events;
}

}  // namespace fesd
