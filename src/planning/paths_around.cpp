#include "fesd_trajopt/planning/paths_around.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fesd {
namespace {

/// A path that touches a disc exactly (a pusher arriving in contact) keeps out of it to rounding.
constexpr double kTouchTolerance = 1e-9;

double distanceToSegment(const Eigen::Vector2d& p, const Eigen::Vector2d& a,
                         const Eigen::Vector2d& b) {
  const Eigen::Vector2d ab = b - a;
  const double squared = ab.squaredNorm();
  const double s = squared > 0.0 ? std::clamp((p - a).dot(ab) / squared, 0.0, 1.0) : 0.0;
  return (a + s * ab - p).norm();
}

}  // namespace

std::vector<Eigen::Vector2d> pathAround(const PathQuery& query) {
  std::vector<KeepOut> discs;
  for (KeepOut disc : query.keep_out) {
    disc.distance = std::min(
        {disc.distance, (query.from - disc.centre).norm(), (query.to - disc.centre).norm()});
    disc.corner = std::max(disc.corner, disc.distance);
    discs.push_back(disc);
  }
  const auto clear = [&](const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    return std::none_of(discs.begin(), discs.end(),
                        [&](const KeepOut& disc) {
                          return distanceToSegment(disc.centre, a, b) <
                                 disc.distance * (1.0 - kTouchTolerance);
                        }) &&
           (!query.passable || query.passable(a, b));
  };
  if (clear(query.from, query.to)) return {query.from, query.to};

  // Nodes: from, to, then each disc's turning points (a polygon circumscribing its corner circle).
  std::vector<Eigen::Vector2d> nodes{query.from, query.to};
  const double outward = 1.0 / std::cos(M_PI / kTurningPointsPerDisc);
  for (const KeepOut& disc : discs) {
    for (int k = 0; k < kTurningPointsPerDisc; ++k) {
      const double angle = 2.0 * M_PI * k / kTurningPointsPerDisc;
      const Eigen::Vector2d p =
          disc.centre + disc.corner * outward * Eigen::Vector2d(std::cos(angle), std::sin(angle));
      const bool inside_a_disc = std::any_of(discs.begin(), discs.end(), [&](const KeepOut& other) {
        return (p - other.centre).norm() < other.distance;
      });
      if (!inside_a_disc && (!query.allowed || query.allowed(p))) nodes.push_back(p);
    }
  }
  for (const Eigen::Vector2d& p : query.waypoints) {
    const bool inside_a_disc = std::any_of(discs.begin(), discs.end(), [&](const KeepOut& disc) {
      return (p - disc.centre).norm() < disc.distance;
    });
    if (!inside_a_disc && (!query.allowed || query.allowed(p))) nodes.push_back(p);
  }
  const int count = static_cast<int>(nodes.size());
  const double infinity = std::numeric_limits<double>::infinity();
  std::vector<double> cost(count, infinity);
  std::vector<int> previous(count, -1);
  std::vector<bool> done(count, false);
  cost[0] = 0.0;
  for (;;) {
    int u = -1;
    for (int v = 0; v < count; ++v) {
      if (!done[v] && cost[v] < infinity && (u < 0 || cost[v] < cost[u])) u = v;
    }
    if (u < 0 || u == 1) break;
    done[u] = true;
    for (int v = 0; v < count; ++v) {
      if (done[v]) continue;
      const double through = cost[u] + (nodes[v] - nodes[u]).norm() + query.leg_cost;
      if (through < cost[v] && clear(nodes[u], nodes[v])) {
        cost[v] = through;
        previous[v] = u;
      }
    }
  }
  if (previous[1] < 0) return {query.from, query.to};
  std::vector<Eigen::Vector2d> path;
  for (int v = 1; v >= 0; v = previous[v]) path.push_back(nodes[v]);
  std::reverse(path.begin(), path.end());
  return path;
}

double signedAngle(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return std::atan2(a.x() * b.y() - a.y() * b.x(), a.dot(b));
}

RoundedPath::RoundedPath(const std::vector<Eigen::Vector2d>& corners, double radius) {
  Eigen::Vector2d from = corners.front();
  const auto straight = [&](const Eigen::Vector2d& to) {
    const double length = (to - from).norm();
    if (length > 0.0) {
      pieces_.push_back(
          {length_, length, from, (to - from) / length, Eigen::Vector2d::Zero(), 0.0, 0.0, 0.0});
      length_ += length;
    }
    from = to;
  };
  for (size_t k = 1; k + 1 < corners.size(); ++k) {
    const Eigen::Vector2d in = (corners[k] - corners[k - 1]).normalized();
    const Eigen::Vector2d out = (corners[k + 1] - corners[k]).normalized();
    const double turn = signedAngle(in, out);
    const double half = std::tan(0.5 * std::fabs(turn));
    if (half < 1e-12) continue;
    // Each arc uses at most half of its pieces, so that neighbouring arcs do not overlap.
    const double room =
        0.5 * std::min((corners[k] - corners[k - 1]).norm(), (corners[k + 1] - corners[k]).norm());
    const double r = std::min(radius, room / half);
    const Eigen::Vector2d enter = corners[k] - r * half * in;
    straight(enter);
    const Eigen::Vector2d normal = (turn > 0.0 ? 1.0 : -1.0) * Eigen::Vector2d(-in.y(), in.x());
    const Eigen::Vector2d centre = enter + r * normal;
    const Eigen::Vector2d away = enter - centre;
    pieces_.push_back(
        {length_, r * std::fabs(turn), enter, in, centre, r, std::atan2(away.y(), away.x()), turn});
    length_ += r * std::fabs(turn);
    from = corners[k] + r * half * out;
  }
  straight(corners.back());
  if (pieces_.empty())
    pieces_.push_back(
        {0.0, 0.0, from, Eigen::Vector2d::UnitX(), Eigen::Vector2d::Zero(), 0.0, 0.0, 0.0});
}

const RoundedPath::Piece& RoundedPath::pieceAt(double& s) const {
  s = std::clamp(s, 0.0, length_);
  size_t k = 0;
  while (k + 1 < pieces_.size() && s > pieces_[k].begin + pieces_[k].length) ++k;
  s -= pieces_[k].begin;
  return pieces_[k];
}

Eigen::Vector2d RoundedPath::at(double s) const {
  const Piece& piece = pieceAt(s);
  if (piece.radius == 0.0) return piece.start + s * piece.direction;
  const double angle = piece.angle + piece.sweep * s / piece.length;
  return piece.centre + piece.radius * Eigen::Vector2d(std::cos(angle), std::sin(angle));
}

Eigen::Vector2d RoundedPath::tangent(double s) const {
  const Piece& piece = pieceAt(s);
  if (piece.radius == 0.0) return piece.direction;
  const double angle = piece.angle + piece.sweep * s / piece.length;
  return (piece.sweep > 0.0 ? 1.0 : -1.0) * Eigen::Vector2d(-std::sin(angle), std::cos(angle));
}

double pathLength(const std::vector<Eigen::VectorXd>& path) {
  double length = 0.0;
  for (size_t k = 1; k < path.size(); ++k) length += (path[k] - path[k - 1]).norm();
  return length;
}

Eigen::VectorXd pointAlong(const std::vector<Eigen::VectorXd>& path, double s) {
  if (path.size() == 2) return path[0] + std::clamp(s, 0.0, 1.0) * (path[1] - path[0]);
  double remaining = std::clamp(s, 0.0, 1.0) * pathLength(path);
  for (size_t k = 1; k < path.size(); ++k) {
    const double piece = (path[k] - path[k - 1]).norm();
    if (remaining <= piece && piece > 0.0) {
      return path[k - 1] + (remaining / piece) * (path[k] - path[k - 1]);
    }
    remaining -= piece;
  }
  return path.back();
}

}  // namespace fesd
