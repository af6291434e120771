#pragma once

#include <functional>
#include <vector>

#include <Eigen/Dense>

namespace fesd {

/// A disc the path keeps out of: no point of the path comes nearer its centre than `distance`;
/// where the path turns round it, it keeps `corner` (>= distance) from it, so that a turn has
/// some room (a rounded corner cuts inside its turning point).
struct KeepOut {
  Eigen::Vector2d centre;
  double distance;
  double corner;
};

/// The question for pathAround: from `from` to `to` keeping out of the discs, the turning points
/// inside a convex region (`allowed`, e.g. walls and a workspace box; empty: the plane), every
/// piece travelled from a to b passing `passable(a, b)` too (empty: any; e.g. what trails the
/// mover along the piece must be clear). Every piece costs `leg_cost` on top of its length, so
/// that fewer turns win a near tie.
struct PathQuery {
  Eigen::Vector2d from, to;
  std::vector<KeepOut> keep_out;
  std::function<bool(const Eigen::Vector2d&)> allowed;
  double leg_cost = 0.0;
  std::function<bool(const Eigen::Vector2d&, const Eigen::Vector2d&)> passable;
  /// Turning points to consider besides those round the discs (e.g. where a last piece into a
  /// tight goal can start).
  std::vector<Eigen::Vector2d> waypoints;
};

/// Turning points per disc: their polygon lies outside the corner circle.
constexpr int kTurningPointsPerDisc = 16;

/// The shortest path (length plus leg_cost per piece) from `from` to `to` as a polyline through
/// turning points on polygons around the discs (a visibility graph searched by Dijkstra in a
/// fixed order, so the same question gives the same path on every machine). A disc that holds
/// `from` or `to` is kept out of only as far as they lie from its centre: what starts or ends
/// near it comes no nearer. Without a path that keeps out of them all: the straight segment.
std::vector<Eigen::Vector2d> pathAround(const PathQuery& query);

/// The signed angle from a to b (counter-clockwise positive), in [-pi, pi].
double signedAngle(const Eigen::Vector2d& a, const Eigen::Vector2d& b);

/// A polyline in the plane with its corners rounded by circular arcs of radius up to `radius`
/// (smaller where a neighbouring piece is too short for it): position and unit tangent by arc
/// length, both continuous, so that a pusher behind a body moving along it turns with it.
class RoundedPath {
 public:
  RoundedPath(const std::vector<Eigen::Vector2d>& corners, double radius);
  double length() const { return length_; }
  Eigen::Vector2d at(double s) const;       ///< s clamped to [0, length]
  Eigen::Vector2d tangent(double s) const;  ///< unit

 private:
  struct Piece {
    double begin, length;
    Eigen::Vector2d start, direction;  ///< a straight piece
    Eigen::Vector2d centre;            ///< an arc: radius > 0
    double radius = 0.0, angle = 0.0, sweep = 0.0;
  };
  const Piece& pieceAt(double& s) const;
  std::vector<Piece> pieces_;
  double length_ = 0.0;
};

/// The length of a polyline (in any dimension).
double pathLength(const std::vector<Eigen::VectorXd>& path);

/// The point at arc length fraction s (clamped to [0, 1]) along a polyline.
Eigen::VectorXd pointAlong(const std::vector<Eigen::VectorXd>& path, double s);

}  // namespace fesd
