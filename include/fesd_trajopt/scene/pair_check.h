#pragma once

#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/scene/scene.h"

namespace fesd {

/// Distance from p to the segment from a to b.
double segmentDistance(const Eigen::VectorXd& p, const Eigen::VectorXd& a,
                       const Eigen::VectorXd& b);

/// The smallest gap between each pair's surfaces along the piecewise-linear path through `path`
/// (states of the scene, in time order), with one forward kinematics per state for all pairs.
/// Exact for centres that move straight between consecutive states (a free body's): it takes the
/// closest approach of the relative position on each segment, not only its ends, so a thin body
/// between two samples is not jumped over. A robot sphere moves on arcs: pass a dense path
/// (densePath). Infinity for an empty path.
std::vector<double> smallestGaps(const Scene& scene, const std::vector<ContactPair>& pairs,
                                 const std::vector<Eigen::VectorXd>& path);
double smallestGap(const Scene& scene, const ContactPair& pair,
                   const std::vector<Eigen::VectorXd>& path);

/// The smallest gap of each pair over the given states only (where a plan holds c >= 0: its
/// stage points); infinity for no state.
std::vector<double> smallestGapsAt(const Scene& scene, const std::vector<ContactPair>& pairs,
                                   const std::vector<Eigen::VectorXd>& states);

/// A pair's gap compared with its margin: closer than `margin` times Scene::pairSize.
bool withinMargin(const Scene& scene, const ContactPair& pair, double gap, double margin);

}  // namespace fesd
