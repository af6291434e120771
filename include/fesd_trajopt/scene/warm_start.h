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
  int intervals = 0, elements = 0, stages = 0;
  bool switch_detection = true;
};

/// A structure of these moving bodies and modelled pairs (names), on this grid.
PlanStructure planStructure(std::vector<std::string> moving_bodies,
                            std::vector<std::string> modelled_pairs, double horizon, int intervals,
                            const DiscretizationOptions& discretization);

/// A free body as PlanStructure::moving_bodies names it: "name (radius r, actuated|passive)".
std::string movingBodyName(const SceneBody& body);

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

/// Which of the candidate pairs (names) a warm start's first round models with lazy pairs: those
/// the previous plan ended with (`previous`), when every one of them is still a candidate, so
/// that the NLPs can match; empty when one is not.
std::vector<bool> previousPairsAmong(const std::vector<std::string>& candidates,
                                     const std::vector<std::string>& previous);

/// Replanning on an accuracy ladder starts on the rung the last plan needed, since its warm
/// start fits only there: `grid` takes the previous plan's stages and elements when that plan
/// (a verified solution) used the same method on a grid at least as fine.
void startOnPreviousRung(const PlanStructure& previous, DiscretizationOptions& grid);

}  // namespace fesd
