#include "fesd_trajopt/scene/pair_check.h"

#include <algorithm>
#include <limits>

namespace fesd {

double segmentDistance(const Eigen::VectorXd& p, const Eigen::VectorXd& a,
                       const Eigen::VectorXd& b) {
  const Eigen::VectorXd d = b - a;
  const double length_squared = d.squaredNorm();
  const double s =
      length_squared > 0.0 ? std::clamp((p - a).dot(d) / length_squared, 0.0, 1.0) : 0.0;
  return (a + s * d - p).norm();
}

std::vector<double> smallestGaps(const Scene& scene, const std::vector<ContactPair>& pairs,
                                 const std::vector<Eigen::VectorXd>& path) {
  const std::vector<CollisionBody> bodies = scene.collisionBodies();
  const int dimension = scene.dimension();
  CentreEvaluator evaluator(scene.robotPointer(), dimension);
  // Each body's centre once per point, not once per pair: a robot's checked pairs share few
  // bodies (231 pairs of 63 spheres for the Panda's bar), and a turning one's costs a sincos.
  std::vector<Eigen::Vector3d> centres(bodies.size());
  // Per pair, its relative position at each point (for a wall: the body's centre).
  std::vector<Eigen::MatrixXd> relative(pairs.size(), Eigen::MatrixXd(dimension, path.size()));
  for (size_t i = 0; i < path.size(); ++i) {
    evaluator.setState(path[i].data());
    for (size_t c = 0; c < bodies.size(); ++c) centres[c] = evaluator.position(bodies[c].centre);
    for (size_t k = 0; k < pairs.size(); ++k) {
      const ContactPair& pair = pairs[k];
      Eigen::Vector3d p = centres.at(pair.body);
      if (pair.kind == ContactPair::Kind::kBody) p -= centres.at(pair.other);
      relative[k].col(i) = p.head(dimension);
      if (pair.kind == ContactPair::Kind::kObstacle) {
        relative[k].col(i) -= scene.obstacles().at(pair.other).position;
      }
    }
  }
  std::vector<double> gaps(pairs.size(), std::numeric_limits<double>::infinity());
  for (size_t k = 0; k < pairs.size(); ++k) {
    const double size = scene.pairSize(pairs[k]);
    if (pairs[k].kind == ContactPair::Kind::kWall) {  // linear in the position: ends are extreme
      const SceneWall& wall = scene.walls().at(pairs[k].other);
      for (Eigen::Index i = 0; i < relative[k].cols(); ++i) {
        gaps[k] = std::min(gaps[k], wall.normal.dot(relative[k].col(i)) - wall.offset - size);
      }
      continue;
    }
    for (Eigen::Index i = 0; i < relative[k].cols(); ++i) {
      const auto a = relative[k].col(i);
      const auto b = relative[k].col(i + 1 < relative[k].cols() ? i + 1 : i);
      const double length_squared = (b - a).squaredNorm();
      const double s =
          length_squared > 0.0 ? std::clamp(-a.dot(b - a) / length_squared, 0.0, 1.0) : 0.0;
      gaps[k] = std::min(gaps[k], (a + s * (b - a)).norm() - size);
    }
  }
  return gaps;
}

double smallestGap(const Scene& scene, const ContactPair& pair,
                   const std::vector<Eigen::VectorXd>& path) {
  return smallestGaps(scene, {pair}, path)[0];
}

std::vector<double> smallestGapsAt(const Scene& scene, const std::vector<ContactPair>& pairs,
                                   const std::vector<Eigen::VectorXd>& states) {
  std::vector<double> gaps(pairs.size(), std::numeric_limits<double>::infinity());
  for (const Eigen::VectorXd& x : states) {
    const std::vector<double> at = scene.pairGaps(pairs, x);
    for (size_t k = 0; k < pairs.size(); ++k) gaps[k] = std::min(gaps[k], at[k]);
  }
  return gaps;
}

bool withinMargin(const Scene& scene, const ContactPair& pair, double gap, double margin) {
  return gap < margin * scene.pairSize(pair);
}

}  // namespace fesd
