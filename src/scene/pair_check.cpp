#include "fesd_trajopt/scene/pair_check.h"

#include <algorithm>
#include <limits>

namespace fesd {
namespace {

/// The pair's relative position (body minus other; for a wall: the body's position).
Eigen::VectorXd relativePosition(const DiscScene& scene, const ContactPair& pair,
                                 const Eigen::VectorXd& x) {
  const Eigen::VectorXd p = scene.position(pair.body, x);
  switch (pair.kind) {
    case ContactPair::Kind::kBody:
      return p - scene.position(pair.other, x);
    case ContactPair::Kind::kObstacle:
      return p - scene.obstacles().at(pair.other).position;
    case ContactPair::Kind::kWall:
      return p;
  }
  return p;
}

}  // namespace

double segmentDistance(const Eigen::VectorXd& p, const Eigen::VectorXd& a,
                       const Eigen::VectorXd& b) {
  const Eigen::VectorXd d = b - a;
  const double length_squared = d.squaredNorm();
  const double s =
      length_squared > 0.0 ? std::clamp((p - a).dot(d) / length_squared, 0.0, 1.0) : 0.0;
  return (a + s * d - p).norm();
}

double pairSize(const DiscScene& scene, const ContactPair& pair) {
  const double radius = scene.bodies().at(pair.body).radius;
  switch (pair.kind) {
    case ContactPair::Kind::kBody:
      return radius + scene.bodies().at(pair.other).radius;
    case ContactPair::Kind::kObstacle:
      return radius + scene.obstacles().at(pair.other).radius;
    case ContactPair::Kind::kWall:
      return radius;
  }
  return radius;
}

double pairGap(const DiscScene& scene, const ContactPair& pair, const Eigen::VectorXd& x) {
  const Eigen::VectorXd relative = relativePosition(scene, pair, x);
  if (pair.kind == ContactPair::Kind::kWall) {
    const SceneWall& wall = scene.walls().at(pair.other);
    return wall.normal.dot(relative) - wall.offset - pairSize(scene, pair);
  }
  return relative.norm() - pairSize(scene, pair);
}

double smallestGap(const DiscScene& scene, const ContactPair& pair,
                   const std::vector<Eigen::VectorXd>& path) {
  double smallest = std::numeric_limits<double>::infinity();
  if (pair.kind == ContactPair::Kind::kWall) {  // linear in the position: the ends are extreme
    for (const Eigen::VectorXd& x : path) smallest = std::min(smallest, pairGap(scene, pair, x));
    return smallest;
  }
  // The relative positions along the path, one column per point (segmentDistance's arithmetic
  // from the origin, without a vector allocated per point).
  const int dimension = scene.dimension();
  const int body = scene.stateIndex(pair.body);
  Eigen::MatrixXd relative(dimension, path.size());
  for (size_t i = 0; i < path.size(); ++i) {
    relative.col(i) = path[i].segment(body, dimension);
    if (pair.kind == ContactPair::Kind::kBody) {
      relative.col(i) -= path[i].segment(scene.stateIndex(pair.other), dimension);
    } else {
      relative.col(i) -= scene.obstacles().at(pair.other).position;
    }
  }
  const double size = pairSize(scene, pair);
  for (Eigen::Index i = 0; i < relative.cols(); ++i) {
    const auto a = relative.col(i);
    const auto b = relative.col(i + 1 < relative.cols() ? i + 1 : i);
    const double length_squared = (b - a).squaredNorm();
    const double s =
        length_squared > 0.0 ? std::clamp(-a.dot(b - a) / length_squared, 0.0, 1.0) : 0.0;
    smallest = std::min(smallest, (a + s * (b - a)).norm() - size);
  }
  return smallest;
}

}  // namespace fesd
