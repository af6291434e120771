#include "fesd_trajopt/scene/push_plan.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <memory>

#include "fesd_trajopt/scene/pair_check.h"

namespace fesd {
namespace {

constexpr double kDegree = M_PI / 180.0;
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
/// A push end is out of the pushers' reach when they can produce less than 90 % of the
/// displacement to it (by magnitude: the residual of their nonnegative combination).
constexpr double kUnpushableFraction = 0.1;
/// Rings searched around an unreachable target, out to the push's length.
constexpr int kSearchRings = 50;

bool insideWorkspace(const BodyTask& task, const Eigen::VectorXd& p) {
  for (int d = 0; d < p.size(); ++d) {
    if (task.workspace_lower.size() && p(d) < task.workspace_lower(d)) return false;
    if (task.workspace_upper.size() && p(d) > task.workspace_upper(d)) return false;
  }
  return true;
}

Eigen::VectorXd clampToWorkspace(const BodyTask& task, Eigen::VectorXd p) {
  if (task.workspace_lower.size()) p = p.cwiseMax(task.workspace_lower);
  if (task.workspace_upper.size()) p = p.cwiseMin(task.workspace_upper);
  return p;
}

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

/// Straight from a to b as s goes from 0 to 1 (clamped).
Eigen::VectorXd along(const Eigen::VectorXd& a, const Eigen::VectorXd& b, double s) {
  return a + std::min(1.0, std::max(0.0, s)) * (b - a);
}

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

/// p on a straight path along `direction` (unit), moved sideways out of the ball (centre,
/// distance): the path goes around the ball on the side the centre leaves free (a fixed side,
/// the first sideways axis, for a path through the centre), continuously.
Eigen::VectorXd besidePath(const Eigen::VectorXd& p, const Eigen::VectorXd& direction,
                           const Eigen::VectorXd& centre, double distance) {
  const Eigen::VectorXd away = p - centre;
  const double ahead = away.dot(direction);
  if (away.norm() >= distance || std::fabs(ahead) >= distance) return p;
  Eigen::VectorXd sideways = away - ahead * direction;
  if (sideways.norm() == 0.0) {
    int axis;
    direction.cwiseAbs().minCoeff(&axis);
    sideways = Eigen::VectorXd::Unit(p.size(), axis) - direction(axis) * direction;
  }
  return centre + ahead * direction +
         std::sqrt(distance * distance - ahead * ahead) * sideways.normalized();
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

/// The planned positions of every body as functions of time, and the forces that move them.
class PlannedMotion {
 public:
  PlannedMotion(const SceneTask& task, const std::vector<ContactPair>& pairs,
                const std::vector<PushAssignment>& pushes, double contact_time, double release_time)
      : task_(task),
        pairs_(pairs),
        pushes_(pushes),
        contact_(contact_time),
        release_(release_time) {
    const Scene& scene = task_.scene;
    for (size_t b = 0; b < scene.bodies().size(); ++b) {
      const int body = static_cast<int>(b);
      const BodyTask& t = task_.bodies[b];
      const bool has_goal = t.target.size() && t.target_weight > 0.0;
      simulated_.push_back(!scene.bodies()[b].actuated && !isPushed(body) && !has_goal &&
                           std::any_of(pairs_.begin(), pairs_.end(),
                                       [&](const ContactPair& p) { return involves(p, body); }));
    }
    if (std::find(simulated_.begin(), simulated_.end(), true) != simulated_.end()) simulate();
  }

  Eigen::VectorXd state(double t) const {
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

  /// The forces of the pairs in contact at t (with a passive side) that move the passive bodies
  /// with their planned velocities, in the least-squares sense with lambda >= 0: first those of
  /// the simulated bodies, which they move exactly as the projection did, then those of the
  /// pushed bodies, which also carry the reactions of what they shove.
  Eigen::VectorXd multipliers(double t) const {
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
      (simulated_[pair.body] || simulated_[other] ? shoving : pushing)
          .push_back(static_cast<int>(k));
    }
    fitForces(shoving, x, v, lambda, true);
    fitForces(pushing, x, v, lambda, false);
    return lambda;
  }

  /// The mean control of [begin, end]: the mean planned velocity of the actuated bodies minus
  /// the mean contact reaction on them (piecewise by the phases, 4 midpoints per piece).
  Eigen::VectorXd meanControl(double begin, double end) const {
    const Scene& scene = task_.scene;
    const int dim = scene.dimension();
    const Eigen::VectorXd velocity = (state(end) - state(begin)) / (end - begin);
    std::vector<double> breaks{begin};
    for (double t : {contact_, release_}) {
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

 private:
  const PushAssignment* pushOf(int body) const {
    for (const PushAssignment& push : pushes_) {
      if (push.pusher == body) return &push;
    }
    return nullptr;
  }
  bool isPushed(int body) const {
    return std::any_of(pushes_.begin(), pushes_.end(),
                       [body](const PushAssignment& p) { return p.pushed == body; });
  }
  bool pushing(int pusher, int pushed, double t) const {
    const PushAssignment* push = pushOf(pusher);
    return push && push->pushed == pushed && t > contact_ && t <= release_;
  }
  bool planned(const ContactPair& pair) const {
    return std::find(pairs_.begin(), pairs_.end(), pair) != pairs_.end();
  }
  Eigen::VectorXd start(int body) const { return task_.scene.bodies()[body].position; }
  /// The task's target, or the start when the body has none.
  Eigen::VectorXd goal(int body, const Eigen::VectorXd& otherwise) const {
    const BodyTask& t = task_.bodies[body];
    return t.target.size() && t.target_weight > 0.0 ? t.target : otherwise;
  }

  /// A pushed body's straight path, moved sideways around the obstacles and off the walls of
  /// its pairs.
  Eigen::VectorXd pushedPosition(int body, double t) const {
    const Scene& scene = task_.scene;
    const Eigen::VectorXd from = start(body), to = goal(body, from);
    Eigen::VectorXd p = along(from, to, (t - contact_) / std::max(release_ - contact_, 1e-300));
    if ((to - from).norm() == 0.0) return p;
    const Eigen::VectorXd direction = (to - from).normalized();
    const double radius = scene.bodies()[body].radius;
    for (int o = 0; o < static_cast<int>(scene.obstacles().size()); ++o) {
      if (!planned({body, ContactPair::Kind::kObstacle, o})) continue;
      const SceneObstacle& obstacle = scene.obstacles()[o];
      p = besidePath(p, direction, obstacle.position, radius + obstacle.radius);
    }
    for (int w = 0; w < static_cast<int>(scene.walls().size()); ++w) {
      if (!planned({body, ContactPair::Kind::kWall, w})) continue;
      const SceneWall& wall = scene.walls()[w];
      const double gap = wall.normal.dot(p) - wall.offset - radius;
      if (gap < 0.0) p -= gap * wall.normal;
    }
    return p;
  }

  Eigen::VectorXd plannedPosition(int body, double t) const {
    const double horizon = task_.horizon;
    if (isPushed(body)) return pushedPosition(body, t);
    const PushAssignment* push = pushOf(body);
    if (!push) return along(start(body), goal(body, start(body)), t / horizon);
    const Eigen::VectorXd pushed_start = start(push->pushed);
    if (t <= contact_) {
      return along(start(body), pushed_start + push->offset, t / std::max(contact_, 1e-300));
    }
    if (t <= release_) return pushedPosition(push->pushed, t) + push->offset;
    const Eigen::VectorXd released = pushedPosition(push->pushed, release_) + push->offset;
    return along(released, goal(body, released),
                 (t - release_) / std::max(horizon - release_, 1e-300));
  }

  /// Every body that is not simulated at its planned position; then the actuated ones step out
  /// of what they would pass through (obstacles, bodies they do not push, walls), in a fixed
  /// order, and stay in their workspaces. Simulated bodies keep their positions in x.
  void placePlannedBodies(double t, Eigen::VectorXd& x) const {
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
        if (scene.bodies()[other].actuated || pushing(b, other, t)) continue;
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

  /// lambda >= 0 of the `active` pairs that best moves the passive bodies among them (the
  /// simulated ones only, or the others) with velocity v, given the forces already in lambda.
  void fitForces(const std::vector<int>& active, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                 Eigen::VectorXd& lambda, bool simulated_bodies) const {
    const Scene& scene = task_.scene;
    std::vector<int> moved;
    for (int k : active) {
      for (int b : {pairs_[k].body, pairs_[k].kind == ContactPair::Kind::kBody ? pairs_[k].other
                                                                               : pairs_[k].body}) {
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

  /// The velocity of the plan just before t (just after, at the start).
  Eigen::VectorXd velocity(double t) const {
    const double dt = kVelocityStep * task_.horizon;
    return t >= dt ? Eigen::VectorXd((state(t) - state(t - dt)) / dt)
                   : Eigen::VectorXd((state(t + dt) - state(t)) / dt);
  }

  /// Moves simulated body b out of everything its pairs name, as the projection would.
  void shove(int b, Eigen::VectorXd& x) const {
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

  /// The simulated bodies over the horizon, in steps short enough that nothing moves farther
  /// than kStepFraction of the smallest radius per step: at each step the planned bodies move
  /// (actuated ones stepping around the simulated ones where they were), then every simulated
  /// body is shoved out of what overlaps it.
  void simulate() {
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
        largest_move =
            std::max(largest_move,
                     (scene.position(b, x) - scene.position(b, previous)).cwiseAbs().maxCoeff());
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

  SceneTask task_;
  std::vector<ContactPair> pairs_;
  std::vector<PushAssignment> pushes_;
  double contact_, release_;
  std::vector<bool> simulated_;  ///< passive bodies without a goal: they move only when pushed
  double sample_step_ = 0.0;
  std::vector<Eigen::VectorXd> samples_;  ///< full states every sample_step_ (when simulating)
};

int bodyPairIndex(const std::vector<ContactPair>& pairs, int a, int b) {
  for (size_t k = 0; k < pairs.size(); ++k) {
    const ContactPair& pair = pairs[k];
    if (pair.kind != ContactPair::Kind::kBody) continue;
    if ((pair.body == a && pair.other == b) || (pair.body == b && pair.other == a)) return k;
  }
  return -1;
}

/// The pushers of one passive body pushed from its start to `end`, placed in index order.
std::vector<PushAssignment> placePushers(const SceneTask& task,
                                         const std::vector<ContactPair>& pairs, int pushed,
                                         const Eigen::VectorXd& end, std::vector<bool>& busy) {
  const Scene& scene = task.scene;
  const Eigen::VectorXd start = scene.bodies()[pushed].position;
  const std::vector<Eigen::VectorXd> candidates = candidateDirections((end - start).normalized());
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
          insideWorkspace(task.bodies[pusher], start + offset) &&
          insideWorkspace(task.bodies[pusher], end + offset) &&
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

/// How much of a displacement the placed pushers cannot produce (relative): each pushes only
/// along its offset, so the displacement must lie in the cone of the offsets.
double unpushableFraction(const std::vector<PushAssignment>& placed,
                          const Eigen::VectorXd& displacement) {
  if (displacement.norm() == 0.0) return 0.0;
  if (placed.empty()) return 1.0;
  Eigen::MatrixXd G(displacement.size(), placed.size());
  for (size_t k = 0; k < placed.size(); ++k) G.col(k) = -placed[k].offset;
  return (G * nonnegativeLeastSquares(G, displacement) - displacement).norm() / displacement.norm();
}

/// The fastest a body moves along unit direction d under a bound on each coordinate's speed.
double speedAlong(double max_speed, const Eigen::VectorXd& d) {
  return max_speed / d.cwiseAbs().maxCoeff();
}

/// The shortest approach and push a body's pushers' speed bounds allow, judged optimistically:
/// the nearest pusher straight to its pose at full speed, then the body at k / (k + 1) of the
/// fastest pusher's speed along the push (the projection shares a push between pushers and
/// pushed: one pusher moves a passive body at half its own speed, k together at k / (k + 1) of
/// theirs). Infinite when no pusher can move.
struct PushTimes {
  double approach = 0.0, push = 0.0;
};
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

/// Whether the placed pushers can push their body from start to end within the horizon
/// (shortestPush), so that only ends clearly out of time are replaced.
bool pushableInTime(const SceneTask& task, const std::vector<PushAssignment>& placed,
                    const Eigen::VectorXd& start, const Eigen::VectorXd& end) {
  if (start == end) return true;
  const PushTimes times = shortestPush(task, placed, start, end);
  return times.approach + times.push <= task.horizon;
}

/// The shortest approach and push phases of all planned pushes (shortestPush per pushed body),
/// so that a push judged in time keeps a push phase; a body no pusher can reach leaves the
/// least-effort phases as they are.
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
    if (wall.normal.dot(p) - wall.offset < radius) return false;
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

/// Where the plan pushes a passive body: its target when the pushers can be placed to push it
/// there (workspace bounds), can push it there in time (pushableInTime) and it is clear of
/// obstacles and walls; otherwise the nearest end
/// that is, with a straight path clear of obstacles, on rings around the target 2 % of the
/// push's length apart, refined by bisection along the direction found (the start if none is).
/// A soft target out of reach then gets a first guess near the best plan, not one that pushes
/// wherever the pushers happen to fit. Returned as a short push (the target itself when it is
/// pushable), marked time_limited when only the time rules the target out.
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
    const std::vector<PushAssignment> placed = placePushers(task, pairs, pushed, end, trial);
    Judgement judgement;
    judgement.placeable = unpushableFraction(placed, end - start) < kUnpushableFraction;
    judgement.in_time = judgement.placeable && pushableInTime(task, placed, start, end);
    return judgement;
  };
  const auto pushable = [&](const Eigen::VectorXd& end) { return judge(end).in_time; };
  // The target's own path may go around obstacles (besidePath); a replacement's may not.
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

}  // namespace

PushPlan planPushes(const SceneTask& task, const std::vector<ContactPair>& pairs) {
  const Scene& scene = task.scene;
  const int count = static_cast<int>(scene.bodies().size()), dim = scene.dimension();
  PushPlan plan;
  SceneTask planned = task;  // with the pushed bodies' ends the pushers can reach
  std::vector<bool> busy(count, false);
  for (int b = 0; b < count; ++b) {
    const BodyTask& t = task.bodies[b];
    if (scene.bodies()[b].actuated || !t.target.size() || !(t.target_weight > 0.0) ||
        (t.target - scene.bodies()[b].position).norm() == 0.0) {
      continue;
    }
    const PushPlan::ShortPush short_push = pushableEnd(task, pairs, b, busy);
    const Eigen::VectorXd end = short_push.end;
    if (end != t.target) plan.short_pushes.push_back(short_push);
    planned.bodies[b].target = end;
    if (end == scene.bodies()[b].position) continue;  // no push: no direction to push from
    const std::vector<PushAssignment> pushers = placePushers(task, pairs, b, end, busy);
    plan.pushes.insert(plan.pushes.end(), pushers.begin(), pushers.end());
  }

  // The impulse (lambda times the push's duration) of each pushing pair: G impulse = the pushed
  // body's displacement, with G's columns grad_{p_pushed} c = 2 (p_pushed - p_pusher) = -2 offset.
  // It sets the phase lengths; the plan's forces come from its motion (PlannedMotion).
  Eigen::VectorXd impulse = Eigen::VectorXd::Zero(pairs.size());
  for (int b = 0; b < count; ++b) {
    std::vector<const PushAssignment*> own;
    for (const PushAssignment& p : plan.pushes) {
      if (p.pushed == b) own.push_back(&p);
    }
    if (own.empty()) continue;
    Eigen::MatrixXd G(dim, own.size());
    for (size_t k = 0; k < own.size(); ++k) G.col(k) = -2.0 * own[k]->offset;
    const Eigen::VectorXd lambda =
        nonnegativeLeastSquares(G, planned.bodies[b].target - scene.bodies()[b].position);
    for (size_t k = 0; k < own.size(); ++k) {
      impulse(bodyPairIndex(pairs, own[k]->pusher, b)) = lambda(k);
    }
  }
  // Phase lengths of least control effort: with straight, uniform motion a phase of length tau
  // costs c / tau, c = the sum of the pushers' squared (control x tau), so tau ~ sqrt(c). In the
  // push a pusher's control is its velocity minus the reaction 2 offset lambda.
  double approach = 0.0, push = 0.0, back = 0.0;
  for (const PushAssignment& p : plan.pushes) {
    const Eigen::VectorXd start = scene.bodies()[p.pushed].position;
    const Eigen::VectorXd target = planned.bodies[p.pushed].target;
    const BodyTask& pusher = task.bodies[p.pusher];
    approach += (start + p.offset - scene.bodies()[p.pusher].position).squaredNorm();
    push += (target - start - 2.0 * p.offset * impulse(bodyPairIndex(pairs, p.pusher, p.pushed)))
                .squaredNorm();
    if (pusher.target.size() && pusher.target_weight > 0.0) {
      back += (pusher.target - target - p.offset).squaredNorm();
    }
  }
  const double total = std::sqrt(approach) + std::sqrt(push) + std::sqrt(back);
  plan.contact_time = plan.release_time = task.horizon;
  if (!plan.pushes.empty() && total > 0.0) {
    plan.contact_time = task.horizon * std::sqrt(approach) / total;
    plan.release_time = task.horizon * (std::sqrt(approach) + std::sqrt(push)) / total;
    // No phase shorter than the speed bounds allow (a push to the edge of what time allows).
    const PushTimes least = leastPhaseTimes(planned, plan.pushes);
    plan.contact_time = std::min(std::max(plan.contact_time, least.approach), task.horizon);
    plan.release_time =
        std::min(std::max(plan.release_time, plan.contact_time + least.push), task.horizon);
  }
  const auto motion = std::make_shared<const PlannedMotion>(planned, pairs, plan.pushes,
                                                            plan.contact_time, plan.release_time);
  plan.guess.state = [motion](double t) { return motion->state(t); };
  plan.guess.multipliers = [motion](double t) { return motion->multipliers(t); };
  for (int k = 0; k < task.num_intervals; ++k) {
    plan.guess.controls.push_back(motion->meanControl(task.horizon * k / task.num_intervals,
                                                      task.horizon * (k + 1) / task.num_intervals));
  }
  return plan;
}

}  // namespace fesd
