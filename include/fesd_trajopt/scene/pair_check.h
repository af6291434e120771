#pragma once

#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/scene/disc_scene.h"

namespace fesd {

/// The length that a pair's margins are relative to: the sum of its radii (a wall has none).
double pairSize(const DiscScene& scene, const ContactPair& pair);

/// Distance from p to the segment from a to b.
double segmentDistance(const Eigen::VectorXd& p, const Eigen::VectorXd& a,
                       const Eigen::VectorXd& b);

/// The signed gap between a pair's surfaces at a state of the scene (negative: overlap).
double pairGap(const DiscScene& scene, const ContactPair& pair, const Eigen::VectorXd& x);

/// The smallest gap between a pair's surfaces along the piecewise-linear path through `path`
/// (states of the scene, in time order): exact for straight motion between consecutive states,
/// since it takes the closest approach of the relative position on each segment, not only its
/// ends. So a thin body between two samples is not jumped over. Infinity for an empty path.
double smallestGap(const DiscScene& scene, const ContactPair& pair,
                   const std::vector<Eigen::VectorXd>& path);

}  // namespace fesd
