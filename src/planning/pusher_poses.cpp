#include "fesd_trajopt/planning/pusher_poses.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>

#include "fesd_trajopt/scene/pair_check.h"

namespace fesd {
namespace {

constexpr double kDegree = M_PI / 180.0;
/// A push end is out of the pushers' reach when they can produce less than 90 % of the
/// displacement to it (by magnitude: the residual of their nonnegative combination).
constexpr double kUnpushableFraction = 0.1;
/// Rings searched around an unreachable target, out to the push's length.
constexpr int kSearchRings = 50;

/// Unit vectors from a pushed body towards candidate pusher poses: straight behind the push
/// first, then tilted away from it in steps of 1 degree (in 2-D to either side, in 3-D towards
/// 12 directions around it).
std::vector<Eigen::VectorXd> candidateDirections(const Eigen::VectorXd& push_direction) {
  const Eigen::VectorXd behind = -push_direction;
  std::vector<Eigen::VectorXd> sideways;
  if (behind.size() == 2) {
    const Eigen::Vector2d normal(-behind(1), behind(0));
    sideways = {normal, -normal};
  } else {
    int axis;
    behind.cwiseAbs().minCoeff(&axis);
    const Eigen::Vector3d b = behind;
    const Eigen::Vector3d e1 = (Eigen::Vector3d::Unit(axis) - b(axis) * b).normalized();
    const Eigen::Vector3d e2 = b.cross(e1);
    for (int k = 0; k < 12; ++k) {
      sideways.push_back(std::cos(30.0 * k * kDegree) * e1 + std::sin(30.0 * k * kDegree) * e2);
    }
  }
  std::vector<Eigen::VectorXd> candidates{behind};
  for (int degrees = 1; degrees < 90; ++degrees) {
    for (const Eigen::VectorXd& side : sideways) {
      candidates.push_back(std::cos(degrees * kDegree) * behind +
                           std::sin(degrees * kDegree) * side);
    }
  }
  return candidates;
}

/// How much of a displacement the placed pushers cannot produce (relative): each pushes only
/// along its offset, so the displacement must lie in the cone of the offsets, and of the normals
/// of the walls the body ends against (`walls`: it slides along them, held by their force).
double unpushableFraction(const std::vector<PushAssignment>& placed,
                          const Eigen::VectorXd& displacement,
                          const std::vector<Eigen::VectorXd>& walls = {}) {
  if (displacement.norm() == 0.0) return 0.0;
  if (placed.empty()) return 1.0;
  Eigen::MatrixXd G(displacement.size(), placed.size() + walls.size());
  for (size_t k = 0; k < placed.size(); ++k) G.col(k) = -placed[k].offset;
  for (size_t k = 0; k < walls.size(); ++k) G.col(placed.size() + k) = walls[k];
  return (G * nonnegativeLeastSquares(G, displacement) - displacement).norm() / displacement.norm();
}

/// Whether a disc of `radius` at p keeps clear of the scene's walls and (with `obstacles`) its
/// obstacles.
bool clearOfFixed(const Scene& scene, double radius, const Eigen::VectorXd& p, bool obstacles) {
  for (const SceneObstacle& obstacle : scene.obstacles()) {
    if (obstacles && (p - obstacle.position).norm() < radius + obstacle.radius) return false;
  }
  for (const SceneWall& wall : scene.walls()) {
    if (wall.normal.dot(p) - wall.offset < radius) return false;
  }
  return true;
}

/// A wall's contact surface for a disc of `radius`: touching it within rounding.
constexpr double kTouching = 1e-9;

/// The normals of the walls a disc of `radius` at p touches.
std::vector<Eigen::VectorXd> touchedWalls(const Scene& scene, double radius,
                                          const Eigen::VectorXd& p) {
  std::vector<Eigen::VectorXd> normals;
  for (const SceneWall& wall : scene.walls()) {
    if (wall.normal.dot(p) - wall.offset - radius <= kTouching) normals.push_back(wall.normal);
  }
  return normals;
}

/// The fastest a body moves along unit direction d under a bound on each coordinate's speed.
double speedAlong(double max_speed, const Eigen::VectorXd& d) {
  return max_speed / d.cwiseAbs().maxCoeff();
}

/// Whether the placed pushers can push their body from start to end within the horizon
/// (shortestPush), so that only ends clearly out of time are replaced.
bool pushableInTime(const SceneTask& task, const std::vector<PushAssignment>& placed,
                    const Eigen::VectorXd& start, const Eigen::VectorXd& end) {
  if (start == end) return true;
  const PushTimes times = shortestPush(task, placed, start, end);
  return times.approach + times.push <= task.horizon;
}

/// Whether a body ends at p clear of the obstacles and walls; with `path_from`, pushed straight
/// there from that start without meeting an obstacle (a replacement end behind an obstacle would
/// need a push around it).
bool clearEnd(const Scene& scene, int body, const Eigen::VectorXd& p,
              const Eigen::VectorXd* path_from = nullptr) {
  const double radius = scene.bodies()[body].radius;
  for (const SceneObstacle& obstacle : scene.obstacles()) {
    const double distance = path_from ? segmentDistance(obstacle.position, *path_from, p)
                                      : (p - obstacle.position).norm();
    if (distance < radius + obstacle.radius) return false;
  }
  for (const SceneWall& wall : scene.walls()) {
    if (wall.normal.dot(p) - wall.offset < radius - kTouching) return false;
  }
  return true;
}

/// Unit directions to search around a point: 72 in the plane, 26 in space (a cube's faces,
/// edges and corners), in a fixed order.
std::vector<Eigen::VectorXd> searchDirections(int dim) {
  std::vector<Eigen::VectorXd> directions;
  if (dim == 2) {
    for (int k = 0; k < 72; ++k) {
      directions.push_back(
          Eigen::Vector2d(std::cos(5.0 * k * kDegree), std::sin(5.0 * k * kDegree)));
    }
    return directions;
  }
  for (int x = -1; x <= 1; ++x) {
    for (int y = -1; y <= 1; ++y) {
      for (int z = -1; z <= 1; ++z) {
        if (x || y || z) directions.push_back(Eigen::Vector3d(x, y, z).normalized());
      }
    }
  }
  return directions;
}

/// The boundary between `reachable` (where `ok` holds) and `unreachable`, halved `halvings`
/// times: the last point found reachable.
double bisect(double reachable, double unreachable, int halvings,
              const std::function<bool(double)>& ok) {
  for (int halving = 0; halving < halvings; ++halving) {
    const double middle = 0.5 * (reachable + unreachable);
    (ok(middle) ? reachable : unreachable) = middle;
  }
  return reachable;
}

/// The radius of the largest actuated body with a pair with `pushed` (0 when none).
double largestPusher(const SceneTask& task, const std::vector<ContactPair>& pairs, int pushed) {
  double largest = 0.0;
  for (int b = 0; b < static_cast<int>(task.scene.bodies().size()); ++b) {
    if (task.scene.bodies()[b].actuated && bodyPairIndex(pairs, b, pushed) >= 0) {
      largest = std::max(largest, task.scene.bodies()[b].radius);
    }
  }
  return largest;
}

}  // namespace

/// lambda >= 0 minimising |G lambda - v| (active set: drop the most negative and solve again).
Eigen::VectorXd nonnegativeLeastSquares(const Eigen::MatrixXd& G, const Eigen::VectorXd& v) {
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(G.cols());
  std::vector<int> free(G.cols());
  for (int j = 0; j < G.cols(); ++j) free[j] = j;
  while (!free.empty()) {
    Eigen::MatrixXd columns(G.rows(), free.size());
    for (size_t k = 0; k < free.size(); ++k) columns.col(k) = G.col(free[k]);
    const Eigen::VectorXd solution = columns.colPivHouseholderQr().solve(v);
    int most_negative;
    if (solution.minCoeff(&most_negative) >= 0.0) {
      for (size_t k = 0; k < free.size(); ++k) lambda(free[k]) = solution(k);
      break;
    }
    free.erase(free.begin() + most_negative);
  }
  return lambda;
}

int bodyPairIndex(const std::vector<ContactPair>& pairs, int a, int b) {
  for (size_t k = 0; k < pairs.size(); ++k) {
    const ContactPair& pair = pairs[k];
    if (pair.kind != ContactPair::Kind::kBody) continue;
    if ((pair.body == a && pair.other == b) || (pair.body == b && pair.other == a)) return k;
  }
  return -1;
}

std::vector<PushAssignment> placePushers(const SceneTask& task,
                                         const std::vector<ContactPair>& pairs, int pushed,
                                         const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                                         std::vector<bool>& busy) {
  const Scene& scene = task.scene;
  const std::vector<Eigen::VectorXd> candidates = candidateDirections((to - from).normalized());
  std::vector<PushAssignment> placed;
  for (int pusher = 0; pusher < static_cast<int>(scene.bodies().size()); ++pusher) {
    if (!scene.bodies()[pusher].actuated || busy[pusher] ||
        bodyPairIndex(pairs, pusher, pushed) < 0) {
      continue;
    }
    const double radius = scene.bodies()[pusher].radius;
    const double distance = radius + scene.bodies()[pushed].radius;
    for (const Eigen::VectorXd& direction : candidates) {
      const Eigen::VectorXd offset = distance * direction;
      const bool fits =
          task.bodies[pusher].insideWorkspace(from + offset) &&
          task.bodies[pusher].insideWorkspace(to + offset) &&
          clearOfFixed(scene, radius, from + offset, true) &&
          clearOfFixed(scene, radius, to + offset, false) &&
          std::all_of(placed.begin(), placed.end(), [&](const PushAssignment& p) {
            return (p.offset - offset).norm() >= radius + scene.bodies()[p.pusher].radius;
          });
      if (!fits) continue;
      placed.push_back({pusher, pushed, offset});
      busy[pusher] = true;
      break;
    }
  }
  return placed;
}

PushTimes shortestPush(const SceneTask& task, const std::vector<PushAssignment>& pushers,
                       const Eigen::VectorXd& start, const Eigen::VectorXd& end) {
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const double length = (end - start).norm();
  PushTimes times{kInfinity, length == 0.0 ? 0.0 : kInfinity};
  double speed = 0.0;
  for (const PushAssignment& push : pushers) {
    const double max_speed = task.bodies[push.pusher].max_speed;
    const Eigen::VectorXd way = start + push.offset - task.scene.bodies()[push.pusher].position;
    const double distance = way.norm();
    times.approach = std::min(
        times.approach, distance == 0.0 ? 0.0 : distance / speedAlong(max_speed, way / distance));
    if (length > 0.0) speed = std::max(speed, speedAlong(max_speed, (end - start) / length));
  }
  const double k = static_cast<double>(pushers.size());
  if (speed > 0.0) times.push = length / (speed * k / (k + 1.0));
  return times;
}

PushTimes leastPhaseTimes(const SceneTask& planned, const std::vector<PushAssignment>& pushes) {
  PushTimes least;
  for (size_t b = 0; b < planned.scene.bodies().size(); ++b) {
    std::vector<PushAssignment> own;
    for (const PushAssignment& push : pushes) {
      if (push.pushed == static_cast<int>(b)) own.push_back(push);
    }
    if (own.empty()) continue;
    const PushTimes times =
        shortestPush(planned, own, planned.scene.bodies()[b].position, planned.bodies[b].target);
    if (std::isfinite(times.approach)) least.approach = std::max(least.approach, times.approach);
    if (std::isfinite(times.push)) least.push = std::max(least.push, times.push);
  }
  return least;
}

PushPlan::ShortPush pushableEnd(const SceneTask& task, const std::vector<ContactPair>& pairs,
                                int pushed, const std::vector<bool>& busy) {
  const Scene& scene = task.scene;
  const Eigen::VectorXd start = scene.bodies()[pushed].position;
  const Eigen::VectorXd target = task.bodies[pushed].target;
  // Whether pushers can be placed to push the body to `end`, and whether also in time.
  struct Judgement {
    bool placeable = false, in_time = false;
  };
  const auto judge = [&](const Eigen::VectorXd& end) {
    std::vector<bool> trial = busy;
    const std::vector<PushAssignment> placed = placePushers(task, pairs, pushed, start, end, trial);
    Judgement judgement;
    const std::vector<Eigen::VectorXd> walls =
        touchedWalls(scene, scene.bodies()[pushed].radius, end);
    judgement.placeable = unpushableFraction(placed, end - start, walls) < kUnpushableFraction;
    judgement.in_time = judgement.placeable && pushableInTime(task, placed, start, end);
    return judgement;
  };
  const auto pushable = [&](const Eigen::VectorXd& end) { return judge(end).in_time; };
  // The target's own path may go around obstacles (legPoints); a replacement's may not.
  const Judgement at_target = clearEnd(scene, pushed, target) ? judge(target) : Judgement{};
  if (at_target.in_time) return {pushed, target};
  PushPlan::ShortPush short_push{pushed, start, at_target.placeable};
  if (short_push.time_limited) {  // as far as time allows on the way to the target
    const double reachable = bisect(0.0, 1.0, 20, [&](double fraction) {
      return pushable(start + fraction * (target - start));
    });
    short_push.end = start + reachable * (target - start);
    return short_push;
  }
  const auto replacement = [&](const Eigen::VectorXd& end) {
    return clearEnd(scene, pushed, end, &start) && pushable(end);
  };
  // Against a wall the body slides along it: the target moved onto the nearest wall it is
  // within a pusher's reach of, before any other end.
  const double radius = scene.bodies()[pushed].radius;
  double nearest = std::numeric_limits<double>::infinity();
  for (const SceneWall& wall : scene.walls()) {
    const double gap = wall.normal.dot(target) - wall.offset - radius;
    const Eigen::VectorXd end = target - gap * wall.normal;
    if (gap >= 0.0 && gap < nearest && gap <= 2.0 * largestPusher(task, pairs, pushed) &&
        replacement(end)) {
      nearest = gap;
      short_push.end = end;
    }
  }
  if (std::isfinite(nearest)) return short_push;
  const double length = (target - start).norm();
  const std::vector<Eigen::VectorXd> directions = searchDirections(scene.dimension());
  const double spacing = length / kSearchRings;
  for (int ring = 1; ring <= kSearchRings; ++ring) {
    for (const Eigen::VectorXd& direction : directions) {
      if (!replacement(target + ring * spacing * direction)) continue;
      // The ring inside was out of reach in this direction: bisect between the two.
      const double reachable = bisect(ring * spacing, (ring - 1) * spacing, 10, [&](double radius) {
        return replacement(target + radius * direction);
      });
      short_push.end = target + reachable * direction;
      return short_push;
    }
  }
  return short_push;
}

}  // namespace fesd
