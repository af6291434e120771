#include "fesd_trajopt/scene/warm_start.h"

#include <algorithm>
#include <cmath>
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
                            const DiscretizationOptions& discretization, double length_unit) {
  PlanStructure structure;
  structure.length_unit = length_unit;
  structure.moving_bodies = std::move(moving_bodies);
  structure.modelled_pairs = std::move(modelled_pairs);
  structure.horizon = horizon;
  structure.intervals = intervals;
  structure.interval_elements = discretization.interval_elements.empty()
                                    ? std::vector<int>(intervals, discretization.num_elements)
                                    : discretization.interval_elements;
  structure.stages = discretization.num_stages;
  structure.switch_detection = discretization.switch_detection;
  return structure;
}

int PlanStructure::largestElements() const {
  return interval_elements.empty()
             ? 0
             : *std::max_element(interval_elements.begin(), interval_elements.end());
}

std::string movingBodyName(const SceneBody& body, double length_unit) {
  std::ostringstream text;
  text << body.name << " (radius " << length_unit * body.radius << ", "
       << (body.actuated ? "actuated" : "passive");
  if (body.turns) text << ", turning, rho " << length_unit * body.turning_radius;
  text << ")";
  return text.str();
}

std::string warmStartMismatch(const PlanStructure& previous, const PlanStructure& now) {
  if (previous.length_unit != now.length_unit) {
    return difference("the scenes' length scales", previous.length_unit, now.length_unit);
  }
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
  if (previous.intervals != now.intervals || previous.interval_elements != now.interval_elements ||
      previous.stages != now.stages || previous.switch_detection != now.switch_detection) {
    const auto grid = [](const PlanStructure& s) {
      const auto [fewest, most] =
          std::minmax_element(s.interval_elements.begin(), s.interval_elements.end());
      const std::string elements = s.interval_elements.empty() ? "0"
                                   : *fewest == *most
                                       ? std::to_string(*most)
                                       : std::to_string(*fewest) + "-" + std::to_string(*most);
      return std::to_string(s.intervals) + " intervals x " + elements +
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

int intervalsDone(const PlanStructure& previous, const PlanStructure& now) {
  const int done = previous.intervals - now.intervals;
  if (done < 0 || now.intervals < 1 || previous.stages != now.stages ||
      previous.switch_detection != now.switch_detection ||
      static_cast<int>(previous.interval_elements.size()) != previous.intervals ||
      static_cast<int>(now.interval_elements.size()) != now.intervals) {
    return -1;
  }
  const double length = previous.horizon / previous.intervals;
  if (std::fabs(now.horizon / now.intervals - length) > 1e-9 * length) return -1;
  for (int k = 0; k < now.intervals; ++k) {
    if (now.interval_elements[k] < previous.interval_elements[done + k]) return -1;
  }
  return done;
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

void startOnPreviousRung(const PlanStructure& previous, int intervals, double horizon,
                         DiscretizationOptions& grid) {
  PlanStructure now = previous;
  now.intervals = intervals;
  now.horizon = horizon;
  now.stages = grid.num_stages;
  now.switch_detection = grid.switch_detection;
  now.interval_elements = grid.interval_elements.empty()
                              ? std::vector<int>(intervals, grid.num_elements)
                              : grid.interval_elements;
  const int done = previous.intervals - intervals;
  if (done < 0 || previous.stages < grid.num_stages ||
      previous.switch_detection != grid.switch_detection ||
      static_cast<int>(previous.interval_elements.size()) != previous.intervals ||
      static_cast<int>(now.interval_elements.size()) != intervals ||
      std::fabs(horizon / intervals - previous.horizon / previous.intervals) >
          1e-9 * previous.horizon / previous.intervals) {
    return;
  }
  const std::vector<int> rest(previous.interval_elements.begin() + done,
                              previous.interval_elements.end());
  for (int k = 0; k < intervals; ++k) {
    if (rest[k] < now.interval_elements[k]) return;
  }
  grid.num_stages = previous.stages;
  grid.interval_elements = rest;
}

}  // namespace fesd
