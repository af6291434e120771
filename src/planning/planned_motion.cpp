#include "fesd_trajopt/planning/planned_motion.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <memory>

#include "fesd_trajopt/planning/paths_around.h"
#include "fesd_trajopt/planning/pusher_poses.h"

namespace fesd {
namespace {

/// A pair with a passive side is in contact in the plan while its gap is at most this fraction
/// of its size: simulated bodies sit on contact only up to the interpolation between steps.
constexpr double kContactGap = 1e-3;
/// Simulated bodies are shoved in steps in which nothing moves farther than this fraction of
/// the smallest radius, so that no contact is stepped over.
constexpr double kStepFraction = 0.05;
/// Sweeps of the projection of simulated bodies per step: enough for short chains.
constexpr int kProjectionSweeps = 4;
/// Velocities of the plan are differences over this fraction of the horizon.
constexpr double kVelocityStep = 1e-7;

Eigen::VectorXd clampToWorkspace(const BodyTask& task, Eigen::VectorXd p) {
  if (task.workspace_lower.size()) p = p.cwiseMax(task.workspace_lower);
  if (task.workspace_upper.size()) p = p.cwiseMin(task.workspace_upper);
  return p;
}

/// Straight from a to b as s goes from 0 to 1 (clamped).
Eigen::VectorXd along(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double s) {
  return a + std::min(1.0, std::max(0.0, s)) * (b - a);
}

/// p moved radially out of the ball (centre, distance), or p itself.
Eigen::VectorXd outside(const Eigen::VectorXd& p, const Eigen::VectorXd& centre, double distance) {
  const Eigen::VectorXd away = p - centre;
  const double length = away.norm();
  if (length >= distance) return p;
  // A path through the very centre leaves along the first axis (a fixed, deterministic choice).
  const Eigen::VectorXd direction =
      length > 0.0 ? Eigen::VectorXd(away / length) : Eigen::VectorXd::Unit(p.size(), 0);
  return centre + distance * direction;
}

bool involves(const ContactPair& pair, int body) {
  return pair.body == body || (pair.kind == ContactPair::Kind::kBody && pair.other == body);
}

/// d c / d p_body of a pair's constraint at x (0 when the body is not in the pair).
Eigen::VectorXd gradientOn(const Scene& scene, const ContactPair& pair, int body,
                           const Eigen::VectorXd& x) {
  const Eigen::VectorXd p = scene.position(pair.body, x);
  switch (pair.kind) {
    case ContactPair::Kind::kBody: {
      const Eigen::VectorXd difference = p - scene.position(pair.other, x);
      if (body == pair.body) return 2.0 * difference;
      if (body == pair.other) return -2.0 * difference;
      break;
    }
    case ContactPair::Kind::kObstacle:
      if (body == pair.body) return 2.0 * (p - scene.obstacles()[pair.other].position);
      break;
    case ContactPair::Kind::kWall:
      if (body == pair.body) return scene.walls()[pair.other].normal;
      break;
  }
  return Eigen::VectorXd::Zero(scene.dimension());
}

}  // namespace

PlannedMotion::PlannedMotion(const SceneTask& task, const std::vector<ContactPair>& pairs,
                             const std::vector<PushLeg>& legs, const std::vector<Transit>& transits)
    : task_(task), pairs_(pairs), legs_(legs), transits_(transits) {
  const Scene& scene = task_.scene;
  const int count = static_cast<int>(scene.bodies().size());
  pieces_.resize(count);
  for (size_t k = 0; k < transits_.size(); ++k) {
    const Transit& transit = transits_[k];
    pieces_[transit.body].push_back({transit.begin, transit.end, static_cast<int>(k), -1, {}});
  }
  for (size_t k = 0; k < legs_.size(); ++k) {
    const PushLeg& leg = legs_[k];
    rounded_.emplace_back();
    if (!leg.through.empty())
      rounded_.back() = std::make_shared<const RoundedPath>(roundedPush(leg));
    pieces_[leg.pushed].push_back({leg.begin, leg.end, -1, static_cast<int>(k), {}});
    for (const PushAssignment& push : leg.pushes) {
      pieces_[push.pusher].push_back({leg.begin, leg.end, -1, static_cast<int>(k), push.offset});
    }
  }
  for (std::vector<Piece>& pieces : pieces_) {
    std::stable_sort(pieces.begin(), pieces.end(),
                     [](const Piece& a, const Piece& b) { return a.begin < b.begin; });
    for (const Piece& piece : pieces) {
      breaks_.push_back(piece.begin);
      breaks_.push_back(piece.end);
    }
  }
  std::sort(breaks_.begin(), breaks_.end());
  breaks_.erase(std::unique(breaks_.begin(), breaks_.end()), breaks_.end());
  for (int b = 0; b < count; ++b) {
    const BodyTask& t = task_.bodies[b];
    const bool has_goal = t.hasTarget();
    const bool pushed = std::any_of(legs_.begin(), legs_.end(),
                                    [b](const PushLeg& leg) { return leg.pushed == b; });
    simulated_.push_back(!scene.bodies()[b].actuated && !pushed && !has_goal &&
                         std::any_of(pairs_.begin(), pairs_.end(),
                                     [&](const ContactPair& p) { return involves(p, b); }));
  }
  if (std::find(simulated_.begin(), simulated_.end(), true) != simulated_.end()) simulate();
}

Eigen::VectorXd PlannedMotion::state(double t) const {
  Eigen::VectorXd x = task_.scene.initialState();
  if (!samples_.empty()) {
    const double position = std::clamp(t / sample_step_, 0.0, samples_.size() - 1.0);
    const size_t m = std::min(static_cast<size_t>(position), samples_.size() - 2);
    const double s = position - m;
    x = (1.0 - s) * samples_[m] + s * samples_[m + 1];
  }
  placePlannedBodies(t, x);
  return x;
}

Eigen::VectorXd PlannedMotion::multipliers(double t) const {
  const Scene& scene = task_.scene;
  const Eigen::VectorXd x = state(t), v = velocity(t);
  Eigen::VectorXd lambda = Eigen::VectorXd::Zero(pairs_.size());
  std::vector<int> shoving, pushing;
  for (size_t k = 0; k < pairs_.size(); ++k) {
    const ContactPair& pair = pairs_[k];
    const int other = pair.kind == ContactPair::Kind::kBody ? pair.other : pair.body;
    const bool passive_side =
        !scene.bodies()[pair.body].actuated || !scene.bodies()[other].actuated;
    if (!passive_side || scene.pairGap(pair, x) > kContactGap * scene.pairSize(pair)) continue;
    (simulated_[pair.body] || simulated_[other] ? shoving : pushing).push_back(static_cast<int>(k));
  }
  fitForces(shoving, x, v, lambda, true);
  fitForces(pushing, x, v, lambda, false);
  return lambda;
}

Eigen::VectorXd PlannedMotion::meanControl(double begin, double end) const {
  const Scene& scene = task_.scene;
  const int dim = scene.dimension();
  const Eigen::VectorXd velocity = (state(end) - state(begin)) / (end - begin);
  std::vector<double> breaks{begin};
  for (double t : breaks_) {
    if (t > begin && t < end) breaks.push_back(t);
  }
  breaks.push_back(end);
  Eigen::VectorXd reaction = Eigen::VectorXd::Zero(scene.stateSize());
  constexpr int kMidpoints = 4;
  for (size_t piece = 0; piece + 1 < breaks.size(); ++piece) {
    const double length = breaks[piece + 1] - breaks[piece];
    for (int m = 0; m < kMidpoints; ++m) {
      const double t = breaks[piece] + (m + 0.5) * length / kMidpoints;
      const Eigen::VectorXd x = state(t), lambda = multipliers(t);
      for (size_t k = 0; k < pairs_.size(); ++k) {
        if (lambda(k) == 0.0) continue;
        for (int b = 0; b < static_cast<int>(scene.bodies().size()); ++b) {
          if (!scene.bodies()[b].actuated || !involves(pairs_[k], b)) continue;
          reaction.segment(scene.stateIndex(b), dim) +=
              lambda(k) * gradientOn(scene, pairs_[k], b, x) * length / kMidpoints;
        }
      }
    }
  }
  Eigen::VectorXd u = Eigen::VectorXd::Zero(scene.controlSize());
  for (int b = 0; b < static_cast<int>(scene.bodies().size()); ++b) {
    if (!scene.bodies()[b].actuated) continue;
    u.segment(scene.controlIndex(b), dim) =
        scene.position(b, velocity) - scene.position(b, reaction) / (end - begin);
  }
  return u;
}

Eigen::VectorXd PlannedMotion::plannedPosition(int body, double t) const {
  Eigen::VectorXd p = task_.scene.bodies()[body].position;
  for (const Piece& piece : pieces_[body]) {
    if (t < piece.begin) break;
    // A piece of no duration (a push at the horizon) is at its end once reached.
    const double s = t >= piece.end ? 1.0 : (t - piece.begin) / (piece.end - piece.begin);
    if (piece.transit >= 0) {
      p = pointAlong(transits_[piece.transit].path, s);
      continue;
    }
    const PushLeg& leg = legs_[piece.leg];
    if (!rounded_[piece.leg]) {
      p = along(leg.from, leg.to, s);
      if (piece.offset.size()) p += piece.offset;
      continue;
    }
    // Along the rounded path, the pushers turned with its tangent.
    const RoundedPath& path = *rounded_[piece.leg];
    const double arc = std::clamp(s, 0.0, 1.0) * path.length();
    p = path.at(arc);
    if (piece.offset.size()) {
      const Eigen::Vector2d now = path.tangent(arc), first = path.tangent(0.0);
      p += Eigen::Rotation2Dd(signedAngle(first, now)) * Eigen::Vector2d(piece.offset);
    }
  }
  return p;
}

bool PlannedMotion::pushing(int pusher, int pushed, double t) const {
  for (const Piece& piece : pieces_[pusher]) {
    if (piece.leg >= 0 && legs_[piece.leg].pushed == pushed && t > piece.begin && t <= piece.end) {
      return true;
    }
  }
  return false;
}

void PlannedMotion::placePlannedBodies(double t, Eigen::VectorXd& x) const {
  const Scene& scene = task_.scene;
  const int dim = scene.dimension(), count = static_cast<int>(scene.bodies().size());
  for (int b = 0; b < count; ++b) {
    if (!simulated_[b]) x.segment(scene.stateIndex(b), dim) = plannedPosition(b, t);
  }
  for (int b = 0; b < count; ++b) {
    if (!scene.bodies()[b].actuated) continue;
    Eigen::VectorXd p = x.segment(scene.stateIndex(b), dim);
    const double radius = scene.bodies()[b].radius;
    for (const SceneObstacle& obstacle : scene.obstacles()) {
      p = outside(p, obstacle.position, radius + obstacle.radius);
    }
    for (int other = 0; other < count; ++other) {
      // Simulated bodies are shoved (simulate), the others the plan does not push gone round.
      if (scene.bodies()[other].actuated || simulated_[other] || pushing(b, other, t)) continue;
      p = outside(p, x.segment(scene.stateIndex(other), dim),
                  radius + scene.bodies()[other].radius);
    }
    for (const SceneWall& wall : scene.walls()) {
      const double gap = wall.normal.dot(p) - wall.offset - radius;
      if (gap < 0.0) p -= gap * wall.normal;
    }
    x.segment(scene.stateIndex(b), dim) = clampToWorkspace(task_.bodies[b], p);
  }
}

void PlannedMotion::fitForces(const std::vector<int>& active, const Eigen::VectorXd& x,
                              const Eigen::VectorXd& v, Eigen::VectorXd& lambda,
                              bool simulated_bodies) const {
  const Scene& scene = task_.scene;
  std::vector<int> moved;
  for (int k : active) {
    for (int b : {pairs_[k].body,
                  pairs_[k].kind == ContactPair::Kind::kBody ? pairs_[k].other : pairs_[k].body}) {
      if (!scene.bodies()[b].actuated && simulated_[b] == simulated_bodies &&
          std::find(moved.begin(), moved.end(), b) == moved.end()) {
        moved.push_back(b);
      }
    }
  }
  if (active.empty() || moved.empty()) return;
  const int dim = scene.dimension();
  Eigen::MatrixXd G(dim * moved.size(), active.size());
  Eigen::VectorXd rhs(dim * moved.size());
  for (size_t i = 0; i < moved.size(); ++i) {
    rhs.segment(dim * i, dim) = scene.position(moved[i], v);
    for (size_t k = 0; k < pairs_.size(); ++k) {  // the reactions fitted before
      if (lambda(k) != 0.0) {
        rhs.segment(dim * i, dim) -= lambda(k) * gradientOn(scene, pairs_[k], moved[i], x);
      }
    }
    for (size_t j = 0; j < active.size(); ++j) {
      G.block(dim * i, j, dim, 1) = gradientOn(scene, pairs_[active[j]], moved[i], x);
    }
  }
  const Eigen::VectorXd solution = nonnegativeLeastSquares(G, rhs);
  for (size_t j = 0; j < active.size(); ++j) lambda(active[j]) = solution(j);
}

Eigen::VectorXd PlannedMotion::velocity(double t) const {
  const double dt = kVelocityStep * task_.horizon;
  return t >= dt ? Eigen::VectorXd((state(t) - state(t - dt)) / dt)
                 : Eigen::VectorXd((state(t + dt) - state(t)) / dt);
}

void PlannedMotion::shove(int b, Eigen::VectorXd& x) const {
  const Scene& scene = task_.scene;
  const int dim = scene.dimension();
  Eigen::VectorXd p = x.segment(scene.stateIndex(b), dim);
  const double radius = scene.bodies()[b].radius;
  for (const ContactPair& pair : pairs_) {
    if (!involves(pair, b)) continue;
    switch (pair.kind) {
      case ContactPair::Kind::kBody: {
        const int other = pair.body == b ? pair.other : pair.body;
        p = outside(p, x.segment(scene.stateIndex(other), dim),
                    radius + scene.bodies()[other].radius);
        break;
      }
      case ContactPair::Kind::kObstacle: {
        const SceneObstacle& obstacle = scene.obstacles()[pair.other];
        p = outside(p, obstacle.position, radius + obstacle.radius);
        break;
      }
      case ContactPair::Kind::kWall: {
        const SceneWall& wall = scene.walls()[pair.other];
        const double gap = wall.normal.dot(p) - wall.offset - radius;
        if (gap < 0.0) p -= gap * wall.normal;
        break;
      }
    }
  }
  x.segment(scene.stateIndex(b), dim) = p;
}

void PlannedMotion::simulate() {
  const Scene& scene = task_.scene;
  double smallest_radius = std::numeric_limits<double>::infinity();
  for (const SceneBody& body : scene.bodies()) {
    smallest_radius = std::min(smallest_radius, body.radius);
  }
  constexpr int kCoarseSteps = 256;
  double largest_move = 0.0;
  Eigen::VectorXd previous = scene.initialState();
  placePlannedBodies(0.0, previous);
  for (int m = 1; m <= kCoarseSteps; ++m) {
    Eigen::VectorXd x = scene.initialState();
    placePlannedBodies(task_.horizon * m / kCoarseSteps, x);
    for (int b = 0; b < static_cast<int>(scene.bodies().size()); ++b) {
      largest_move = std::max(
          largest_move, (scene.position(b, x) - scene.position(b, previous)).cwiseAbs().maxCoeff());
    }
    previous = x;
  }
  const int refinement = static_cast<int>(
      std::clamp(std::ceil(largest_move / (kStepFraction * smallest_radius)), 1.0, 256.0));
  const int steps = kCoarseSteps * refinement;
  sample_step_ = task_.horizon / steps;
  samples_.reserve(steps + 1);
  samples_.push_back(scene.initialState());
  for (int m = 1; m <= steps; ++m) {
    Eigen::VectorXd x = samples_.back();
    placePlannedBodies(m * sample_step_, x);
    for (int sweep = 0; sweep < kProjectionSweeps; ++sweep) {
      for (int b = 0; b < static_cast<int>(scene.bodies().size()); ++b) {
        if (simulated_[b]) shove(b, x);
      }
    }
    samples_.push_back(x);
  }
}

}  // namespace fesd
