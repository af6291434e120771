#include "fesd_trajopt/scene/warm_start.h"

#include <algorithm>
#include <sstream>
#include <utility>

namespace fesd {
namespace {

/// "what differs: before -> now".
template <class Value>
std::string difference(const std::string& what, const Value& before, const Value& now) {
  std::ostringstream text;
  text << what << " differ: " << before << " -> " << now;
  return text.str();
}

std::string joined(const std::vector<std::string>& items) {
  std::string text;
  for (const std::string& item : items) text += (text.empty() ? "" : ", ") + item;
  return "[" + text + "]";
}

}  // namespace

PlanStructure planStructure(std::vector<std::string> moving_bodies,
                            std::vector<std::string> modelled_pairs, double horizon, int intervals,
                            const DiscretizationOptions& discretization) {
  PlanStructure structure;
  structure.moving_bodies = std::move(moving_bodies);
  structure.modelled_pairs = std::move(modelled_pairs);
  structure.horizon = horizon;
  structure.intervals = intervals;
  structure.elements = discretization.num_elements;
  structure.stages = discretization.num_stages;
  structure.switch_detection = discretization.switch_detection;
  return structure;
}

std::string movingBodyName(const SceneBody& body) {
  std::ostringstream text;
  text << body.name << " (radius " << body.radius << ", "
       << (body.actuated ? "actuated" : "passive") << ")";
  return text.str();
}

std::string warmStartMismatch(const PlanStructure& previous, const PlanStructure& now) {
  if (previous.moving_bodies != now.moving_bodies) {
    return difference("the moving bodies", joined(previous.moving_bodies),
                      joined(now.moving_bodies));
  }
  if (previous.modelled_pairs != now.modelled_pairs) {
    return difference("the modelled contact pairs", joined(previous.modelled_pairs),
                      joined(now.modelled_pairs));
  }
  if (previous.horizon != now.horizon) {
    return difference("the horizons", previous.horizon, now.horizon);
  }
  if (previous.intervals != now.intervals || previous.elements != now.elements ||
      previous.stages != now.stages || previous.switch_detection != now.switch_detection) {
    const auto grid = [](const PlanStructure& s) {
      return std::to_string(s.intervals) + " intervals x " + std::to_string(s.elements) +
             " elements, n_s = " + std::to_string(s.stages) +
             (s.switch_detection ? ", FESD" : ", standard");
    };
    return difference("the discretisations", grid(previous), grid(now));
  }
  return "";
}

std::string warmStartRefusal(bool solved, int point_size, const NlpSizes& previous_sizes,
                             const PlanStructure& previous, const NlpSizes& now_sizes,
                             const PlanStructure& now) {
  // Only a solution of its NLP will do: an interrupted solve may hold another stage's point.
  if (!solved || point_size != previous_sizes.variables) return "no previous solution";
  const std::string mismatch = warmStartMismatch(previous, now);
  if (!mismatch.empty()) return mismatch;
  if (previous_sizes.variables != now_sizes.variables ||
      previous_sizes.constraints != now_sizes.constraints) {
    const auto sizes = [](const NlpSizes& s) {
      return std::to_string(s.variables) + " variables, " + std::to_string(s.constraints) +
             " constraints";
    };
    return difference("the NLP sizes", sizes(previous_sizes), sizes(now_sizes));
  }
  return "";
}

std::vector<bool> previousPairsAmong(const std::vector<std::string>& candidates,
                                     const std::vector<std::string>& previous) {
  std::vector<bool> chosen(candidates.size(), false);
  size_t found = 0;
  for (size_t k = 0; k < candidates.size(); ++k) {
    chosen[k] = std::find(previous.begin(), previous.end(), candidates[k]) != previous.end();
    found += chosen[k];
  }
  return found == previous.size() ? chosen : std::vector<bool>{};
}

void startOnPreviousRung(const PlanStructure& previous, DiscretizationOptions& grid) {
  if (previous.stages >= grid.num_stages && previous.elements >= grid.num_elements &&
      previous.switch_detection == grid.switch_detection) {
    grid.num_stages = previous.stages;
    grid.num_elements = previous.elements;
  }
}

}  // namespace fesd
