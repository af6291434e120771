#include "fesd_trajopt/planning/turning_push.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <Eigen/Geometry>

#include "fesd_trajopt/planning/paths_around.h"

namespace fesd {
namespace {

/// Start headings tried (one per degree): a deterministic search, the same on every machine.
constexpr int kHeadings = 360;
/// Beyond this turn the corner of a straight-arc-straight path goes to infinity.
constexpr double kLargestTurn = 175.0 * M_PI / 180.0;
/// Below this turn the push is one straight line (the NLP finds the rest).
constexpr double kSmallestTurn = M_PI / 180.0;
/// Contacts and clearances are judged to this fraction of the radii.
constexpr double kTolerance = 1e-9;
/// Ways round a body's spheres turn this much farther out than the pusher touches them.
constexpr double kCornerRoom = 1.1;
/// A pair is in contact in the plan while its gap is at most this fraction of its size.
constexpr double kContactGap = 1e-6;
/// Velocities of the plan are differences over this fraction of the horizon.
constexpr double kVelocityStep = 1e-7;
/// Samples per control interval of its mean control.
constexpr int kControlSamples = 8;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

Eigen::Vector2d unit(double angle) {
  return {std::cos(angle), std::sin(angle)};
}

/// A body's path: `straight_before` along `heading`, an arc of `radius` turning by `turn`, then
/// `straight_after`; its tangent turns with the arc only.
struct TurningPath {
  Eigen::Vector2d from;
  double heading = 0.0, straight_before = 0.0, radius = 0.0, turn = 0.0, straight_after = 0.0;

  double arc() const { return radius * std::fabs(turn); }
  double length() const { return straight_before + arc() + straight_after; }
  /// How far the tangent has turned at arc length l.
  double turned(double l) const {
    if (radius == 0.0) return 0.0;
    return std::copysign(std::clamp(l - straight_before, 0.0, arc()) / radius, turn);
  }
  Eigen::Vector2d at(double l) const {
    const Eigen::Vector2d enter = from + std::min(l, straight_before) * unit(heading);
    if (l <= straight_before || radius == 0.0) return enter;
    const Eigen::Vector2d centre =
        enter +
        std::copysign(radius, turn) * Eigen::Vector2d(-std::sin(heading), std::cos(heading));
    const Eigen::Vector2d exit = centre + Eigen::Rotation2Dd(turned(l)) * (enter - centre);
    return exit + std::max(0.0, l - straight_before - arc()) * unit(heading + turn);
  }
};

/// One push of a plan: the body's path from its pose, the contacts on its straight pieces and on
/// its arc.
struct Leg {
  TurningPath path;
  double yaw = 0.0;  ///< the body's at the start
  PushContact straight, turn;
};

/// A plan's pushes, in order (the pusher goes round the body between them), and its cost: their
/// length, how far the straight pieces' lever would turn the body (as a length: rho times the
/// angle) and, between pushes, the pusher's way from one contact to the next.
struct Layout {
  std::vector<Leg> legs;
  double cost = std::numeric_limits<double>::infinity();
};

/// The contact of least |lever| (the first of equals), or none.
std::optional<PushContact> straightContact(const std::vector<PushContact>& contacts) {
  std::optional<PushContact> best;
  for (const PushContact& c : contacts) {
    if (!best || std::fabs(c.lever) < std::fabs(best->lever)) best = c;
  }
  return best;
}

Eigen::Vector2d pushDirection(double yaw, double heading) {
  return Eigen::Rotation2Dd(-yaw) * unit(heading);
}

/// A straight push from `from` to `to` at `yaw`, or none (no contact pushes that way).
std::optional<Leg> straightLeg(const SceneBody& body, double pusher_radius,
                               const Eigen::Vector2d& from, const Eigen::Vector2d& to, double yaw) {
  const Eigen::Vector2d shift = to - from;
  const double heading = std::atan2(shift.y(), shift.x());
  const std::optional<PushContact> contact =
      straightContact(pushContacts(body, pusher_radius, pushDirection(yaw, heading)));
  if (!contact) return std::nullopt;
  return Leg{{from, heading, shift.norm(), 0.0, 0.0, 0.0}, yaw, *contact, *contact};
}

double legCost(const Leg& leg, double rho) {
  const double straight = leg.path.straight_before + leg.path.straight_after;
  return leg.path.length() + straight * std::fabs(leg.straight.lever) / rho;
}

/// The pusher's place in the world at a leg's start or end.
Eigen::Vector2d contactAt(const Leg& leg, bool at_end) {
  const double l = at_end ? leg.path.length() : 0.0;
  const PushContact& contact = leg.path.radius > 0.0 && (at_end ? leg.path.straight_after == 0.0
                                                                : leg.path.straight_before == 0.0)
                                   ? leg.turn
                                   : leg.straight;
  return leg.path.at(l) + Eigen::Rotation2Dd(leg.yaw + leg.path.turned(l)) * contact.pusher;
}

/// Keeps the cheaper of `best` and `legs` (a detour between two legs costs the pusher's way
/// from one contact to the next, straight, taken twice for the way round the body).
void keepCheaper(std::vector<Leg> legs, double rho, Layout& best) {
  legs.erase(std::remove_if(legs.begin(), legs.end(),
                            [](const Leg& leg) { return leg.path.length() < kTolerance; }),
             legs.end());
  if (legs.empty()) return;
  double cost = 0.0;
  for (size_t k = 0; k < legs.size(); ++k) {
    cost += legCost(legs[k], rho);
    if (k > 0) cost += 2.0 * (contactAt(legs[k], false) - contactAt(legs[k - 1], true)).norm();
  }
  if (cost < best.cost) best = {std::move(legs), cost};
}

/// The cheapest plan from `from` at `yaw` by `shift`, turning by `turn`: one push along a
/// straight line, an arc and a straight line (its push direction fixed in the body's frame), or
/// a push along an arc alone and a straight push, in either order; over every start heading
/// and arc contact.
Layout bestLayout(const SceneBody& body, double pusher_radius, const Eigen::Vector2d& from,
                  double yaw, const Eigen::Vector2d& shift, double turn) {
  const double rho = body.turning_radius;
  const Eigen::Vector2d to = from + shift;
  Layout best;
  if (std::fabs(turn) < kSmallestTurn) {
    if (std::optional<Leg> leg = straightLeg(body, pusher_radius, from, to, yaw)) {
      keepCheaper({*leg}, rho, best);
    }
    return best;
  }
  Eigen::Matrix2d pieces;
  pieces << 1.0, std::cos(turn), 0.0, std::sin(turn);
  for (int i = 0; i < kHeadings; ++i) {
    const double heading = 2.0 * M_PI * i / kHeadings - M_PI;
    const std::vector<PushContact> contacts =
        pushContacts(body, pusher_radius, pushDirection(yaw, heading));
    const std::optional<PushContact> straight = straightContact(contacts);
    if (!straight) continue;
    // In the frame of the heading: shift = a e1 + chord u(turn / 2) + b u(turn).
    const Eigen::Vector2d local = Eigen::Rotation2Dd(-heading) * shift;
    for (const PushContact& contact : contacts) {
      if (contact.lever * turn <= 0.0) continue;
      const double radius = rho * rho / std::fabs(contact.lever);
      const double chord = 2.0 * radius * std::sin(0.5 * std::fabs(turn));
      const Eigen::Vector2d straights = pieces.inverse() * (local - chord * unit(0.5 * turn));
      if (straights.minCoeff() >= 0.0) {
        keepCheaper(
            {{{from, heading, straights(0), radius, turn, straights(1)}, yaw, *straight, contact}},
            rho, best);
      }
      // The turn last, into the target (its push direction at the start's yaw, as this one's).
      const Eigen::Vector2d into = to - chord * unit(heading + 0.5 * turn);
      if (std::optional<Leg> first = straightLeg(body, pusher_radius, from, into, yaw)) {
        keepCheaper({*first, {{into, heading, 0.0, radius, turn, 0.0}, yaw, contact, contact}}, rho,
                    best);
      }
      // The turn first, from the start, then straight to the target.
      const Leg turn_first{{from, heading, 0.0, radius, turn, 0.0}, yaw, contact, contact};
      if (std::optional<Leg> then = straightLeg(
              body, pusher_radius, turn_first.path.at(turn_first.path.length()), to, yaw + turn)) {
        keepCheaper({turn_first, *then}, rho, best);
      }
    }
  }
  return best;
}

/// The pusher's way in the body's frame from one contact to another, round the spheres.
class ContactChange {
 public:
  ContactChange(const SceneBody& body, double pusher_radius, const Eigen::Vector2d& from,
                const Eigen::Vector2d& to) {
    PathQuery query{from, to, {}, {}, 0.0, {}, {}};
    for (const FreeBodySphere& sphere : body.spheres) {
      const double distance = sphere.radius + pusher_radius;
      query.keep_out.push_back({sphere.offset.head<2>(), distance, kCornerRoom * distance});
    }
    for (const Eigen::Vector2d& point : pathAround(query)) way_.push_back(point);
  }
  double length() const { return pathLength(way_); }
  Eigen::Vector2d at(double s) const { return pointAlong(way_, s); }

 private:
  std::vector<Eigen::VectorXd> way_;
};

/// Where the pusher sits in the body's frame at arc length l of a leg: behind the straight
/// contact, the turning one on the arc, changing over a window at each end of the arc.
class PusherPlacement {
 public:
  PusherPlacement(const SceneBody& body, double pusher_radius, const Leg& leg)
      : path_(leg.path),
        straight_(leg.straight.pusher),
        turning_(leg.turn.pusher),
        in_(body, pusher_radius, straight_, turning_),
        out_(body, pusher_radius, turning_, straight_) {
    // About as long as the pusher's way between the contacts: it moves twice as fast as the body.
    const double arc = path_.arc();
    window_in_ = std::min({0.5 * path_.straight_before, 0.25 * arc, 0.5 * in_.length()});
    window_out_ = std::min({0.5 * path_.straight_after, 0.25 * arc, 0.5 * out_.length()});
  }

  Eigen::Vector2d at(double l) const {
    if (path_.radius == 0.0) return straight_;
    const double enter = path_.straight_before, leave = enter + path_.arc();
    if (l < enter - window_in_) return straight_;
    if (l < enter + window_in_) return in_.at((l - enter + window_in_) / (2.0 * window_in_));
    if (l <= leave - window_out_) return turning_;
    if (l < leave + window_out_) return out_.at((l - leave + window_out_) / (2.0 * window_out_));
    return straight_;
  }

 private:
  TurningPath path_;
  Eigen::Vector2d straight_, turning_;
  ContactChange in_, out_;
  double window_in_ = 0.0, window_out_ = 0.0;
};

/// The plan's motion: the pusher's way to each leg's first contact round the body at rest
/// (transits[k] before legs[k]), then the leg; phase k's transit ends at transit_ends[k], its
/// leg at leg_ends[k] (the last at the horizon).
struct TurningMotion {
  std::vector<Leg> legs;
  std::vector<PusherPlacement> placements;
  std::vector<std::vector<Eigen::VectorXd>> transits;
  std::vector<double> transit_ends, leg_ends;
  int pusher = 0, pushed = 1;
  double rho = 1.0;

  /// The scene's state at t, from `initial`.
  Eigen::VectorXd state(const Scene& scene, Eigen::VectorXd x, double t) const {
    const int p = scene.stateIndex(pusher), b = scene.stateIndex(pushed);
    double begin = 0.0;
    for (size_t k = 0; k < legs.size(); ++k) {
      const TurningPath& path = legs[k].path;
      x.segment(b, 2) = path.from;
      x(b + 2) = rho * legs[k].yaw;
      if (t < transit_ends[k]) {
        const double span = transit_ends[k] - begin;
        x.segment(p, 2) = pointAlong(transits[k], span > 0.0 ? (t - begin) / span : 1.0);
        return x;
      }
      const double l =
          path.length() * std::min(1.0, (t - transit_ends[k]) / (leg_ends[k] - transit_ends[k]));
      const double yaw = legs[k].yaw + path.turned(l);
      x.segment(b, 2) = path.at(l);
      x(b + 2) = rho * yaw;
      x.segment(p, 2) = path.at(l) + Eigen::Rotation2Dd(yaw) * placements[k].at(l);
      if (t < leg_ends[k] || k + 1 == legs.size()) return x;
      begin = leg_ends[k];
    }
    return x;
  }
};

bool withinBounds(const BodyTask& task, const Eigen::Vector2d& p) {
  return (task.workspace_lower.size() == 0 || (p.array() >= task.workspace_lower.array()).all()) &&
         (task.workspace_upper.size() == 0 || (p.array() <= task.workspace_upper.array()).all());
}

/// The one pusher and the one turning body with a pose to reach, or (-1, -1).
std::pair<int, int> pusherAndBody(const SceneTask& task) {
  const Scene& scene = task.scene;
  if (scene.dimension() != 2 || scene.hasRobot() || scene.bodies().size() != 2 ||
      !scene.obstacles().empty() || !scene.walls().empty()) {
    return {-1, -1};
  }
  for (int pusher = 0; pusher < 2; ++pusher) {
    const int pushed = 1 - pusher;
    const SceneBody& p = scene.bodies()[pusher];
    const SceneBody& b = scene.bodies()[pushed];
    if (p.actuated && p.spheres.empty() && !task.bodies[pusher].hasTarget() && b.turns &&
        task.bodies[pushed].hasTarget() && task.bodies[pushed].hasYawTarget()) {
      return {pusher, pushed};
    }
  }
  return {-1, -1};
}

}  // namespace

std::vector<PushContact> pushContacts(const SceneBody& body, double pusher_radius,
                                      const Eigen::Vector2d& n) {
  std::vector<PushContact> contacts;
  for (size_t k = 0; k < body.spheres.size(); ++k) {
    const Eigen::Vector2d centre = body.spheres[k].offset.head<2>();
    const Eigen::Vector2d q = centre - (body.spheres[k].radius + pusher_radius) * n;
    bool reachable = true;
    for (size_t j = 0; j < body.spheres.size() && reachable; ++j) {
      if (j == k) continue;
      // The pusher comes along -n towards q: its nearest approach to sphere j on that ray.
      const Eigen::Vector2d w = body.spheres[j].offset.head<2>() - q;
      const double behind = std::max(0.0, -w.dot(n));
      reachable =
          (w + behind * n).norm() >= (body.spheres[j].radius + pusher_radius) * (1.0 - kTolerance);
    }
    if (reachable) contacts.push_back({static_cast<int>(k), q, cross(centre, n)});
  }
  return contacts;
}

std::optional<PushPlan> planTurningPush(const SceneTask& task,
                                        const std::vector<ContactPair>& pairs) {
  const auto [pusher, pushed] = pusherAndBody(task);
  if (pusher < 0) return std::nullopt;
  const Scene scene = task.scene;  // the guess outlives the caller's task
  const SceneBody& body = scene.bodies()[pushed];
  const double pusher_radius = scene.bodies()[pusher].radius;
  // The pair of the pusher with each sphere, in the order of the body's spheres.
  const int pusher_collision = scene.freeBodyCollisionBodies(pusher).front();
  std::vector<int> pair_of_sphere;
  for (const int sphere : scene.freeBodyCollisionBodies(pushed)) {
    const auto found = std::find_if(pairs.begin(), pairs.end(), [&](const ContactPair& pair) {
      return pair.kind == ContactPair::Kind::kBody &&
             ((pair.body == pusher_collision && pair.other == sphere) ||
              (pair.body == sphere && pair.other == pusher_collision));
    });
    if (found == pairs.end()) return std::nullopt;
    pair_of_sphere.push_back(static_cast<int>(found - pairs.begin()));
  }
  const Eigen::Vector2d from = body.position.head<2>();
  const Eigen::Vector2d to = task.bodies[pushed].target.head<2>();
  const double turn = task.bodies[pushed].target_yaw - body.yaw;
  if (std::fabs(turn) > kLargestTurn) return std::nullopt;
  const Layout layout = bestLayout(body, pusher_radius, from, body.yaw, to - from, turn);
  if (!std::isfinite(layout.cost)) return std::nullopt;

  // The pusher's ways round the body to each leg's first contact; the phases by least effort
  // (a pusher moves a body at about half its own speed).
  TurningMotion motion;
  motion.pusher = pusher;
  motion.pushed = pushed;
  motion.rho = body.turning_radius;
  motion.legs = layout.legs;
  double effort = 0.0;
  Eigen::Vector2d at = scene.bodies()[pusher].position.head<2>();
  for (const Leg& leg : layout.legs) {
    motion.placements.emplace_back(body, pusher_radius, leg);
    PathQuery query{at, contactAt(leg, false), {}, {}, 0.0, {}, {}};
    for (const FreeBodySphere& sphere : body.spheres) {
      const double distance = sphere.radius + pusher_radius;
      query.keep_out.push_back(
          {leg.path.from + Eigen::Rotation2Dd(leg.yaw) * sphere.offset.head<2>(), distance,
           kCornerRoom * distance});
    }
    motion.transits.emplace_back();
    for (const Eigen::Vector2d& point : pathAround(query)) {
      if (!withinBounds(task.bodies[pusher], point)) return std::nullopt;
      motion.transits.back().push_back(point);
    }
    effort += pathLength(motion.transits.back()) + 2.0 * leg.path.length();
    at = contactAt(leg, true);
  }
  const double horizon = task.horizon;
  // Too far for the pusher's speed: the disc plan pushes as far as time allows.
  if (effort > task.bodies[pusher].max_speed * horizon) return std::nullopt;
  double time = 0.0;
  for (size_t k = 0; k < layout.legs.size(); ++k) {
    time += horizon * pathLength(motion.transits[k]) / effort;
    motion.transit_ends.push_back(time);
    time += horizon * 2.0 * layout.legs[k].path.length() / effort;
    motion.leg_ends.push_back(k + 1 == layout.legs.size() ? horizon : time);
  }
  const Eigen::VectorXd initial = scene.initialState();
  const auto state = [=](double t) { return motion.state(scene, initial, t); };
  for (int k = 0; k <= 256; ++k) {
    const Eigen::VectorXd x = state(horizon * k / 256.0);
    if (!withinBounds(task.bodies[pusher], x.segment(scene.stateIndex(pusher), 2)) ||
        !withinBounds(task.bodies[pushed], x.segment(scene.stateIndex(pushed), 2))) {
      return std::nullopt;
    }
  }
  const auto velocity = [=](double t) {
    const double dt = kVelocityStep * horizon;
    return t >= dt ? Eigen::VectorXd((state(t) - state(t - dt)) / dt)
                   : Eigen::VectorXd((state(t + dt) - state(t)) / dt);
  };
  // The force of the pusher's pair in contact that moves the body (position and s) along the
  // plan: c = |p_P - p_S|^2 - (r_P + r_S)^2 with p_S = p_B + R(s / rho) o.
  const int count = static_cast<int>(pairs.size());
  const double rho = body.turning_radius;
  const auto multipliers = [=](double t) {
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(count);
    const Eigen::VectorXd x = state(t), v = velocity(t);
    const int p = scene.stateIndex(pusher), b = scene.stateIndex(pushed);
    if (v.segment<3>(b).squaredNorm() == 0.0) return lambda;
    const double yaw = x(b + 2) / rho;
    for (size_t k = 0; k < body.spheres.size(); ++k) {
      const Eigen::Vector2d turned = Eigen::Rotation2Dd(yaw) * body.spheres[k].offset.head<2>();
      const Eigen::Vector2d d = x.segment<2>(p) - x.segment<2>(b) - turned;
      const double size = body.spheres[k].radius + pusher_radius;
      if (d.norm() - size > kContactGap * size) continue;
      Eigen::Vector3d gradient;
      gradient << -2.0 * d, -2.0 * d.dot(Eigen::Vector2d(-turned.y(), turned.x())) / rho;
      lambda(pair_of_sphere[k]) =
          std::max(0.0, gradient.dot(v.segment<3>(b)) / gradient.squaredNorm());
      break;
    }
    return lambda;
  };

  PushPlan plan;
  plan.turns_bodies = true;
  plan.contact_time = motion.transit_ends.front();
  plan.release_time = horizon;
  for (size_t k = 0; k < layout.legs.size(); ++k) {
    const Leg& leg = layout.legs[k];
    const TurningPath& path = leg.path;
    const Eigen::Vector2d end = path.at(path.length());
    plan.transits.push_back({pusher, k == 0 ? 0.0 : motion.leg_ends[k - 1], motion.transit_ends[k],
                             motion.transits[k]});
    const PushAssignment push{pusher, pushed, Eigen::VectorXd(contactAt(leg, false) - path.from)};
    if (k == 0) plan.pushes.push_back(push);
    PushLeg drawn{pushed, path.from, end, motion.transit_ends[k], motion.leg_ends[k],
                  {push}, {},        0.0};
    if (path.radius > 0.0) {  // the corner where its straight pieces (or arc's tangents) meet
      const double reach = path.straight_before + path.radius * std::tan(0.5 * std::fabs(turn));
      drawn.through.push_back(Eigen::VectorXd(path.from + reach * unit(path.heading)));
      drawn.turn_radius = path.radius;
    }
    plan.legs.push_back(drawn);
  }
  plan.guess.state = state;
  plan.guess.multipliers = multipliers;
  const double interval = horizon / task.num_intervals;
  const int p = scene.stateIndex(pusher), b = scene.stateIndex(pushed);
  for (int j = 0; j < task.num_intervals; ++j) {
    const double begin = j * interval;
    Eigen::Vector2d reaction = Eigen::Vector2d::Zero();
    for (int m = 0; m < kControlSamples; ++m) {
      const Eigen::VectorXd x = state(begin + (m + 0.5) * interval / kControlSamples);
      const Eigen::VectorXd lambda = multipliers(begin + (m + 0.5) * interval / kControlSamples);
      for (size_t k = 0; k < body.spheres.size(); ++k) {
        if (lambda(pair_of_sphere[k]) == 0.0) continue;
        const Eigen::Vector2d centre =
            x.segment<2>(b) + Eigen::Rotation2Dd(x(b + 2) / rho) * body.spheres[k].offset.head<2>();
        reaction += lambda(pair_of_sphere[k]) * 2.0 * (x.segment<2>(p) - centre) / kControlSamples;
      }
    }
    const Eigen::VectorXd moved = state(begin + interval) - state(begin);
    Eigen::VectorXd u = Eigen::VectorXd::Zero(scene.controlSize());
    u.segment(scene.controlIndex(pusher), 2) = moved.segment<2>(p) / interval - reaction;
    plan.guess.controls.push_back(u);
  }
  return plan;
}

}  // namespace fesd
