#pragma once

#include <string>
#include <vector>

#include "fesd_trajopt/discretization/discretization_options.h"
#include "fesd_trajopt/scene/scene.h"

namespace fesd {

/// The sizes of the NLP a task became.
struct NlpSizes {
  int variables = 0, constraints = 0, complementarities = 0;
};

/// What a warm start needs unchanged besides the NLP's sizes: what moves (bodies, a robot's
/// joints), the modelled pairs and the discretisation. Targets, initial positions, bounds and
/// weights may differ.
struct PlanStructure {
  std::vector<std::string> moving_bodies;   ///< "name (radius r, actuated|passive)", joints
  std::vector<std::string> modelled_pairs;  ///< the scene's pair names
  double horizon = 0.0;
  int intervals = 0, stages = 0;
  std::vector<int> interval_elements;  ///< elements per control interval
  bool switch_detection = true;
  /// The length unit of the solve (Scene::length_unit): its NLP's point is in it.
  double length_unit = 1.0;

  int largestElements() const;  ///< the most elements of any interval (0 without intervals)
};

/// A structure of these moving bodies and modelled pairs (names), on this grid.
PlanStructure planStructure(std::vector<std::string> moving_bodies,
                            std::vector<std::string> modelled_pairs, double horizon, int intervals,
                            const DiscretizationOptions& discretization, double length_unit = 1.0);

/// A free body as PlanStructure::moving_bodies names it: "name (radius r, actuated|passive)".
/// Its lengths in the user's units: times `length_unit` (Scene::length_unit).
std::string movingBodyName(const SceneBody& body, double length_unit = 1.0);

/// Why a solution of structure `previous` cannot warm-start a task of structure `now`; "" when
/// it can.
std::string warmStartMismatch(const PlanStructure& previous, const PlanStructure& now);

/// Why an earlier solve cannot warm-start one whose NLP is built (sizes and structure known):
/// "no previous solution" unless it solved its NLP (`solved`) and holds that NLP's point
/// (`point_size` values), then warmStartMismatch, then other NLP sizes; "" when it can. Shared
/// by disc and robot tasks.
std::string warmStartRefusal(bool solved, int point_size, const NlpSizes& previous_sizes,
                             const PlanStructure& previous, const NlpSizes& now_sizes,
                             const PlanStructure& now);

/// How many control intervals of a previous plan a replan starts after: the same interval length,
/// stages and method, `now` having k fewer intervals (k >= 0) with at least as many elements in
/// each as the previous plan's interval k + i; -1 when it is not so. Such a replan starts from the
/// rest of the previous plan (laterPart) whatever its bodies and pairs.
int intervalsDone(const PlanStructure& previous, const PlanStructure& now);

/// Which of the candidate pairs (names) a warm start's first round models with lazy pairs: those
/// the previous plan ended with (`previous`), when every one of them is still a candidate, so
/// that the NLPs can match; empty when one is not.
std::vector<bool> previousPairsAmong(const std::vector<std::string>& candidates,
                                     const std::vector<std::string>& previous);

/// A replan starts on the grid the last plan needed, since its warm start fits only there:
/// `grid` takes the previous plan's stages and elements per interval (of the intervals still to
/// come when `horizon` is shorter by whole intervals: intervalsDone) when that plan (a solution
/// of its NLP) used the same method on a grid at least as fine in every interval.
void startOnPreviousRung(const PlanStructure& previous, int intervals, double horizon,
                         DiscretizationOptions& grid);

}  // namespace fesd
