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
/// Beyond this turn the straight pieces along an arc's tangents meet far away (half a turn:
/// never).
constexpr double kLargestTurn = 175.0 * M_PI / 180.0;
/// Below this turn the push is one straight line (the NLP finds the rest).
constexpr double kSmallestTurn = M_PI / 180.0;
/// Contacts are judged to this fraction of the radii; pushes shorter than it times the turning
/// radius are dropped (the plan then ends within that of the target).
constexpr double kTolerance = 1e-9;
/// Ways round a body's spheres turn this much farther out than the pusher touches them.
constexpr double kCornerRoom = 1.1;
/// Velocities of the plan are differences over this fraction of the horizon.
constexpr double kVelocityStep = 1e-7;
/// Points an arc of the plan is drawn through.
constexpr int kArcPoints = 16;
/// Samples per control interval of its mean control.
constexpr int kControlSamples = 8;

double cross(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

Eigen::Vector2d unit(double angle) {
  return {std::cos(angle), std::sin(angle)};
}

/// The contact behind sphere k along n (body frame), or none when the pusher coming along -n
/// would meet another sphere first.
std::optional<PushContact> contactBehind(const SceneBody& body, double pusher_radius, int k,
                                         const Eigen::Vector2d& n) {
  const Eigen::Vector2d centre = body.spheres[k].offset.head<2>();
  const Eigen::Vector2d q = centre - (body.spheres[k].radius + pusher_radius) * n;
  for (int j = 0; j < static_cast<int>(body.spheres.size()); ++j) {
    if (j == k) continue;
    // The pusher comes along -n towards q: its nearest approach to sphere j on that ray.
    const Eigen::Vector2d w = body.spheres[j].offset.head<2>() - q;
    const double behind = std::max(0.0, -w.dot(n));
    if ((w + behind * n).norm() < (body.spheres[j].radius + pusher_radius) * (1.0 - kTolerance)) {
      return std::nullopt;
    }
  }
  return PushContact{k, q, cross(centre, n)};
}

/// The contacts for every degree of push direction in the body's frame, found once (each is
/// quadratic in the spheres).
class ContactTable {
 public:
  ContactTable(const SceneBody& body, double pusher_radius)
      : body_(body), pusher_radius_(pusher_radius) {
    for (int i = 0; i < kHeadings; ++i) {
      contacts_.push_back(pushContacts(body, pusher_radius, direction(i)));
    }
  }
  static Eigen::Vector2d direction(int i) { return unit(2.0 * M_PI * i / kHeadings - M_PI); }
  const std::vector<PushContact>& at(int i) const { return contacts_[i]; }

  /// The reachable contact of least |lever| (the first of equals) along n, or none: the spheres
  /// reachable at the nearest degree tried first, in order of lever, each checked along n.
  std::optional<PushContact> leastLever(const Eigen::Vector2d& n) const {
    const double turns = (std::atan2(n.y(), n.x()) + M_PI) / (2.0 * M_PI);
    const int i = static_cast<int>(std::lround(turns * kHeadings)) % kHeadings;
    std::vector<int> spheres;
    for (const PushContact& c : contacts_[i]) spheres.push_back(c.sphere);
    const auto lever = [&](int k) {
      return std::fabs(cross(body_.spheres[k].offset.head<2>(), n));
    };
    std::stable_sort(spheres.begin(), spheres.end(),
                     [&](int a, int b) { return lever(a) < lever(b); });
    for (int k : spheres) {
      if (std::optional<PushContact> c = contactBehind(body_, pusher_radius_, k, n)) return c;
    }
    std::optional<PushContact> best;
    for (const PushContact& c : pushContacts(body_, pusher_radius_, n)) {
      if (!best || std::fabs(c.lever) < std::fabs(best->lever)) best = c;
    }
    return best;
  }

 private:
  const SceneBody& body_;
  double pusher_radius_;
  std::vector<std::vector<PushContact>> contacts_;
};

/// One push of a plan: the body from `from` at `yaw` along `heading`, straight for `length` or,
/// with a radius, along an arc turning by `turn` (its tangent and the body turning together), the
/// pusher behind `contact` all along.
struct Leg {
  Eigen::Vector2d from;
  double yaw = 0.0, heading = 0.0, length = 0.0, radius = 0.0, turn = 0.0;
  PushContact contact;

  double pathLength() const { return radius > 0.0 ? radius * std::fabs(turn) : length; }
  /// How far the body has turned at arc length l.
  double turned(double l) const {
    return radius > 0.0 ? std::copysign(std::clamp(l, 0.0, pathLength()) / radius, turn) : 0.0;
  }
  Eigen::Vector2d at(double l) const {
    if (radius == 0.0) return from + std::clamp(l, 0.0, length) * unit(heading);
    const Eigen::Vector2d centre =
        from + std::copysign(radius, turn) * Eigen::Vector2d(-std::sin(heading), std::cos(heading));
    return centre + Eigen::Rotation2Dd(turned(l)) * (from - centre);
  }
  Eigen::Vector2d end() const { return at(pathLength()); }
  Eigen::Vector2d pusherAt(double l) const {
    return at(l) + Eigen::Rotation2Dd(yaw + turned(l)) * contact.pusher;
  }
};

/// A plan's pushes, in order (the pusher going round the body at rest between them), and its
/// cost: their length, how far the straight pushes' lever would turn the body (as a length: rho
/// times the angle), and the pusher's way from each contact to the next.
struct Layout {
  std::vector<Leg> legs;
  double cost = std::numeric_limits<double>::infinity();
};

Eigen::Vector2d pushDirection(double yaw, double heading) {
  return Eigen::Rotation2Dd(-yaw) * unit(heading);
}

/// A straight push from `from` to `to` at `yaw` behind the contact of least |lever|, or none (no
/// contact pushes that way).
std::optional<Leg> straightLeg(const ContactTable& contacts, const Eigen::Vector2d& from,
                               const Eigen::Vector2d& to, double yaw) {
  const Eigen::Vector2d shift = to - from;
  const double heading = std::atan2(shift.y(), shift.x());
  const std::optional<PushContact> best = contacts.leastLever(pushDirection(yaw, heading));
  if (!best) return std::nullopt;
  return Leg{from, yaw, heading, shift.norm(), 0.0, 0.0, *best};
}

/// Keeps the cheaper of `best` and `legs` (those of any length; a detour between two legs costs
/// the pusher's way from one contact to the next, straight, taken twice for the way round).
void keepCheaper(std::vector<Leg> legs, double rho, Layout& best) {
  legs.erase(std::remove_if(legs.begin(), legs.end(),
                            [&](const Leg& leg) { return leg.pathLength() < kTolerance * rho; }),
             legs.end());
  if (legs.empty()) return;
  double cost = 0.0;
  for (size_t k = 0; k < legs.size(); ++k) {
    const Leg& leg = legs[k];
    cost += leg.pathLength();
    if (leg.radius == 0.0) cost += leg.length * std::fabs(leg.contact.lever) / rho;
    if (k > 0) {
      cost += 2.0 * (leg.pusherAt(0.0) - legs[k - 1].pusherAt(legs[k - 1].pathLength())).norm();
    }
  }
  if (cost < best.cost) best = {std::move(legs), cost};
}

/// The cheapest plan from `from` at `yaw` by `shift`, turning by `turn`, of a push along an arc
/// (the contact's lever setting its curvature) between two straight pushes along the arc's
/// tangents, either of them or both of no length, or an arc and a straight push to the target in
/// either order; over every push direction in the body's frame (each degree) and arc contact.
Layout bestLayout(const ContactTable& contacts, double rho, const Eigen::Vector2d& from, double yaw,
                  const Eigen::Vector2d& shift, double turn) {
  const Eigen::Vector2d to = from + shift;
  Layout best;
  if (std::fabs(turn) < kSmallestTurn) {
    if (std::optional<Leg> leg = straightLeg(contacts, from, to, yaw)) {
      keepCheaper({*leg}, rho, best);
    }
    return best;
  }
  Eigen::Matrix2d pieces;
  pieces << 1.0, std::cos(turn), 0.0, std::sin(turn);
  for (int i = 0; i < kHeadings; ++i) {
    const Eigen::Vector2d n = ContactTable::direction(i);
    const double heading = yaw + std::atan2(n.y(), n.x());
    // In the frame of the heading: shift = a e1 + chord u(turn / 2) + b u(turn).
    const Eigen::Vector2d local = Eigen::Rotation2Dd(-heading) * shift;
    for (const PushContact& contact : contacts.at(i)) {
      if (contact.lever * turn <= 0.0) continue;
      const double radius = rho * rho / std::fabs(contact.lever);
      const double chord = 2.0 * radius * std::sin(0.5 * std::fabs(turn));
      const auto arc = [&](const Eigen::Vector2d& start) {
        return Leg{start, yaw, heading, 0.0, radius, turn, contact};
      };
      const Eigen::Vector2d straights = pieces.inverse() * (local - chord * unit(0.5 * turn));
      if (straights.minCoeff() >= 0.0) {
        const Eigen::Vector2d enter = from + straights(0) * unit(heading);
        const Leg turning = arc(enter);
        const std::optional<Leg> before = straightLeg(contacts, from, enter, yaw);
        const std::optional<Leg> after = straightLeg(contacts, turning.end(), to, yaw + turn);
        if ((before || straights(0) == 0.0) && (after || straights(1) == 0.0)) {
          std::vector<Leg> legs;
          if (before) legs.push_back(*before);
          legs.push_back(turning);
          if (after) legs.push_back(*after);
          keepCheaper(legs, rho, best);
        }
      }
      // The turn last, into the target, after a straight push to where it starts.
      const Eigen::Vector2d into = to - chord * unit(heading + 0.5 * turn);
      if (std::optional<Leg> first = straightLeg(contacts, from, into, yaw)) {
        keepCheaper({*first, arc(into)}, rho, best);
      }
      // The turn first, then a straight push to the target.
      if (std::optional<Leg> then = straightLeg(contacts, arc(from).end(), to, yaw + turn)) {
        keepCheaper({arc(from), *then}, rho, best);
      }
    }
  }
  return best;
}

/// The gradient of a pusher-sphere constraint c = |p_P - p_S|^2 - (r_P + r_S)^2 on the body's
/// (p, s), p_S = p_B + R(s / rho) o: d = p_P - p_S, `turned` = R(s / rho) o.
Eigen::Vector3d contactGradient(const Eigen::Vector2d& d, const Eigen::Vector2d& turned,
                                double rho) {
  Eigen::Vector3d gradient;
  gradient << -2.0 * d, -2.0 * d.dot(Eigen::Vector2d(-turned.y(), turned.x())) / rho;
  return gradient;
}

/// The pusher's command per unit of a leg's path (constant along it, in the body's frame): its
/// own velocity less the contact's reaction, the force that moves the body along the leg. A
/// straight push through the centre: 2 (the pusher moves the body at half its speed); on an arc
/// the pusher also swings round with the body.
double commandPerLength(const Leg& leg, const SceneBody& body) {
  const double rho = body.turning_radius;
  const double curvature = leg.radius > 0.0 ? std::copysign(1.0 / leg.radius, leg.turn) : 0.0;
  const Eigen::Vector2d tangent = unit(leg.heading - leg.yaw);
  const Eigen::Vector2d q = leg.contact.pusher;
  const Eigen::Vector2d o = body.spheres[leg.contact.sphere].offset.head<2>();
  const Eigen::Vector2d d = q - o;
  const Eigen::Vector3d gradient = contactGradient(d, o, rho);
  Eigen::Vector3d motion;  // the body's (p, s) per length
  motion << tangent, rho * curvature;
  const double lambda = std::max(0.0, gradient.dot(motion) / gradient.squaredNorm());
  const Eigen::Vector2d own = tangent + curvature * Eigen::Vector2d(-q.y(), q.x());
  return (own - 2.0 * lambda * d).norm();
}

/// The plan's motion: the pusher's way to each leg's contact round the body at rest
/// (transits[k] before legs[k], ending at transit_ends[k]), then the leg (ending at
/// leg_ends[k], the last at the horizon).
struct TurningMotion {
  std::vector<Leg> legs;
  std::vector<std::vector<Eigen::VectorXd>> transits;
  std::vector<double> transit_ends, leg_ends;
  int pusher = 0, pushed = 1;
  double rho = 1.0;

  /// The scene's state at t, from `x` (the initial state).
  Eigen::VectorXd state(const Scene& scene, Eigen::VectorXd x, double t) const {
    const int p = scene.stateIndex(pusher), b = scene.stateIndex(pushed);
    double begin = 0.0;
    for (size_t k = 0; k < legs.size(); ++k) {
      const Leg& leg = legs[k];
      x.segment(b, 2) = leg.from;
      x(b + 2) = rho * leg.yaw;
      if (t < transit_ends[k]) {
        const double span = transit_ends[k] - begin;
        x.segment(p, 2) = pointAlong(transits[k], span > 0.0 ? (t - begin) / span : 1.0);
        return x;
      }
      const double l =
          leg.pathLength() * std::min(1.0, (t - transit_ends[k]) / (leg_ends[k] - transit_ends[k]));
      x.segment(b, 2) = leg.at(l);
      x(b + 2) = rho * (leg.yaw + leg.turned(l));
      x.segment(p, 2) = leg.pusherAt(l);
      if (t < leg_ends[k] || k + 1 == legs.size()) return x;
      begin = leg_ends[k];
    }
    return x;
  }

  /// The leg pushing at t, or -1 while the pusher is on its way.
  int legAt(double t) const {
    for (size_t k = 0; k < legs.size(); ++k) {
      if (t < transit_ends[k]) return -1;
      if (t < leg_ends[k] || k + 1 == legs.size()) return static_cast<int>(k);
    }
    return -1;
  }
};

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
  for (int k = 0; k < static_cast<int>(body.spheres.size()); ++k) {
    if (std::optional<PushContact> c = contactBehind(body, pusher_radius, k, n)) {
      contacts.push_back(*c);
    }
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
  const ContactTable contacts(body, pusher_radius);
  const Layout layout = bestLayout(contacts, body.turning_radius, from, body.yaw, to - from, turn);
  if (!std::isfinite(layout.cost)) return std::nullopt;

  // The pusher's ways round the body to each leg's first contact; the phases by least effort:
  // each takes the horizon's share of the pusher's command it needs.
  TurningMotion motion;
  motion.pusher = pusher;
  motion.pushed = pushed;
  motion.rho = body.turning_radius;
  motion.legs = layout.legs;
  double effort = 0.0;
  std::vector<double> leg_efforts;
  Eigen::Vector2d at = scene.bodies()[pusher].position.head<2>();
  for (const Leg& leg : layout.legs) {
    PathQuery query{at, leg.pusherAt(0.0), {}, {}, 0.0, {}, {}};
    for (const FreeBodySphere& sphere : body.spheres) {
      const double distance = sphere.radius + pusher_radius;
      query.keep_out.push_back({leg.from + Eigen::Rotation2Dd(leg.yaw) * sphere.offset.head<2>(),
                                distance, kCornerRoom * distance});
    }
    motion.transits.emplace_back();
    for (const Eigen::Vector2d& point : pathAround(query)) {
      if (!task.bodies[pusher].insideWorkspace(point)) return std::nullopt;
      motion.transits.back().push_back(point);
    }
    leg_efforts.push_back(commandPerLength(leg, body) * leg.pathLength());
    effort += pathLength(motion.transits.back()) + leg_efforts.back();
    at = leg.pusherAt(leg.pathLength());
  }
  const double horizon = task.horizon;
  // Too far for the pusher's speed: the disc plan pushes as far as time allows.
  if (effort > task.bodies[pusher].max_speed * horizon) return std::nullopt;
  double time = 0.0;
  for (size_t k = 0; k < layout.legs.size(); ++k) {
    time += horizon * pathLength(motion.transits[k]) / effort;
    motion.transit_ends.push_back(time);
    time += horizon * leg_efforts[k] / effort;
    motion.leg_ends.push_back(k + 1 == layout.legs.size() ? horizon : time);
  }
  const Eigen::VectorXd initial = scene.initialState();
  const auto state = [=](double t) { return motion.state(scene, initial, t); };
  for (int k = 0; k <= 256; ++k) {
    const Eigen::VectorXd x = state(horizon * k / 256.0);
    if (!task.bodies[pusher].insideWorkspace(x.segment(scene.stateIndex(pusher), 2)) ||
        !task.bodies[pushed].insideWorkspace(x.segment(scene.stateIndex(pushed), 2))) {
      return std::nullopt;
    }
  }
  const auto velocity = [=](double t) {
    const double dt = kVelocityStep * horizon;
    return t >= dt ? Eigen::VectorXd((state(t) - state(t - dt)) / dt)
                   : Eigen::VectorXd((state(t + dt) - state(t)) / dt);
  };
  // The force of the pushing leg's contact that moves the body (position and s) along the plan:
  // its projection on the contact's gradient (>= 0).
  const int count = static_cast<int>(pairs.size());
  const double rho = body.turning_radius;
  const auto multipliers = [=](double t) {
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(count);
    const int leg = motion.legAt(t);
    if (leg < 0) return lambda;
    const Eigen::VectorXd x = state(t), v = velocity(t);
    const int p = scene.stateIndex(pusher), b = scene.stateIndex(pushed);
    const int k = motion.legs[leg].contact.sphere;
    const Eigen::Vector2d turned =
        Eigen::Rotation2Dd(x(b + 2) / rho) * body.spheres[k].offset.head<2>();
    const Eigen::Vector2d d = x.segment<2>(p) - x.segment<2>(b) - turned;
    const Eigen::Vector3d gradient = contactGradient(d, turned, rho);
    lambda(pair_of_sphere[k]) =
        std::max(0.0, gradient.dot(v.segment<3>(b)) / gradient.squaredNorm());
    return lambda;
  };

  PushPlan plan;
  plan.turns_bodies = true;
  plan.contact_time = motion.transit_ends.front();
  plan.release_time = horizon;
  for (size_t k = 0; k < layout.legs.size(); ++k) {
    const Leg& leg = layout.legs[k];
    plan.transits.push_back({pusher, k == 0 ? 0.0 : motion.leg_ends[k - 1], motion.transit_ends[k],
                             motion.transits[k]});
    const PushAssignment push{pusher, pushed, Eigen::VectorXd(leg.pusherAt(0.0) - leg.from)};
    if (k == 0) plan.pushes.push_back(push);
    PushLeg drawn{pushed, leg.from, leg.end(), motion.transit_ends[k], motion.leg_ends[k],
                  {push}, {},       0.0};
    if (leg.radius > 0.0) {  // the arc drawn through points along it
      for (int m = 1; m < kArcPoints; ++m) {
        drawn.through.push_back(Eigen::VectorXd(leg.at(leg.pathLength() * m / kArcPoints)));
      }
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
