#include "fesd_trajopt/planning/push_plan.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>

#include "fesd_trajopt/planning/paths_around.h"
#include "fesd_trajopt/planning/planned_motion.h"
#include "fesd_trajopt/planning/pusher_poses.h"
#include "fesd_trajopt/scene/pair_check.h"

namespace fesd {
namespace {

/// Transits keep this fraction of a pair's size from what they go round, and turns of legs leave
/// that much more room: within the lazy pairs' margin, so that the pairs a plan passes are
/// modelled from the first round.
constexpr double kClearance = 0.05;

bool hasGoal(const BodyTask& t) {
  return t.target.size() && t.target_weight > 0.0;
}

bool insideWorkspace(const BodyTask& task, const Eigen::Vector2d& p) {
  for (int d = 0; d < 2; ++d) {
    if (task.workspace_lower.size() && p(d) < task.workspace_lower(d)) return false;
    if (task.workspace_upper.size() && p(d) > task.workspace_upper(d)) return false;
  }
  return true;
}

/// Turning points of a body of radius `room` (around its centre) inside its workspace and at
/// least `room` from every wall.
std::function<bool(const Eigen::Vector2d&)> roomFor(const SceneTask& task, int body, double room) {
  return [&task, body, room](const Eigen::Vector2d& p) {
    for (const SceneWall& wall : task.scene.walls()) {
      if (wall.normal.head<2>().dot(p) - wall.offset < room) return false;
    }
    return insideWorkspace(task.bodies[body], p);
  };
}

std::vector<Eigen::VectorXd> inScene(const std::vector<Eigen::Vector2d>& path) {
  return std::vector<Eigen::VectorXd>(path.begin(), path.end());
}

/// An actuated body's path from `from` to `to` round the obstacles and the passive bodies at
/// `rest` (their positions meanwhile); `touched` (-1: none), the body it arrives at or leaves in
/// contact, is kept out of at exactly the contact distance. Straight in space.
std::vector<Eigen::VectorXd> transitPath(const SceneTask& task, int body,
                                         const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                                         const std::vector<Eigen::VectorXd>& rest, int touched) {
  const Scene& scene = task.scene;
  if (scene.dimension() != 2 || from == to) return {from, to};
  const double radius = scene.bodies()[body].radius;
  PathQuery query;
  query.from = from;
  query.to = to;
  for (const SceneObstacle& obstacle : scene.obstacles()) {
    const double distance = (1.0 + kClearance) * (obstacle.radius + radius);
    query.keep_out.push_back({obstacle.position, distance, distance});
  }
  for (size_t b = 0; b < scene.bodies().size(); ++b) {
    if (scene.bodies()[b].actuated) continue;
    const double contact = scene.bodies()[b].radius + radius;
    const double distance = static_cast<int>(b) == touched ? contact : (1.0 + kClearance) * contact;
    query.keep_out.push_back({rest[b], distance, (1.0 + kClearance) * contact});
  }
  query.allowed = roomFor(task, body, (1.0 + kClearance) * radius);
  return inScene(pathAround(query));
}

/// The turning points of a pushed body's legs from its start to `end`: round the obstacles (as
/// near as touching: a straight push that grazes a post is still the push to plan), its pusher
/// (radius `pusher_radius`, straight behind it) clear of them too along each leg, with room at
/// each turn for the pusher to go round it; fewer legs win near ties (a leg costs half a turn of
/// a pusher round it). Straight in space.
std::vector<Eigen::VectorXd> legPoints(const SceneTask& task, int pushed,
                                       const Eigen::VectorXd& end, double pusher_radius) {
  const Scene& scene = task.scene;
  const Eigen::VectorXd start = scene.bodies()[pushed].position;
  if (scene.dimension() != 2) return {start, end};
  const double radius = scene.bodies()[pushed].radius;
  PathQuery query;
  query.from = start;
  query.to = end;
  for (const SceneObstacle& obstacle : scene.obstacles()) {
    query.keep_out.push_back(
        {obstacle.position, obstacle.radius + radius,
         (1.0 + kClearance) * (obstacle.radius + radius + 2.0 * pusher_radius)});
  }
  query.passable = [&scene, behind = radius + pusher_radius, pusher_radius](
                       const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d back = -behind * (b - a).normalized();
    return std::all_of(
        scene.obstacles().begin(), scene.obstacles().end(), [&](const SceneObstacle& obstacle) {
          return segmentDistance(obstacle.position, Eigen::VectorXd(a + back),
                                 Eigen::VectorXd(b + back)) >= obstacle.radius + pusher_radius;
        });
  };
  query.allowed = roomFor(task, pushed, radius + 2.0 * pusher_radius);
  query.leg_cost = M_PI * (radius + pusher_radius);
  // Where a first leg can end or a last one start when the pusher has no room near the ends.
  for (const Eigen::VectorXd& centre : {start, end}) {
    for (int ring = 1; ring <= 3; ++ring) {
      for (int k = 0; k < kTurningPointsPerDisc; ++k) {
        const double angle = 2.0 * M_PI * k / kTurningPointsPerDisc;
        query.waypoints.push_back(centre.head<2>() +
                                  ring * (radius + pusher_radius) *
                                      Eigen::Vector2d(std::cos(angle), std::sin(angle)));
      }
    }
  }
  return inScene(pathAround(query));
}

double squaredLength(const std::vector<Eigen::VectorXd>& path) {
  const double length = pathLength(path);
  return length * length;
}

/// The legs of one pushed body along `points` with the pushers of its straight push, each placed
/// anew for its leg's direction; empty when one of them finds no pose for a leg.
std::vector<PushLeg> legsAlong(const SceneTask& task, const std::vector<ContactPair>& pairs,
                               int pushed, const std::vector<Eigen::VectorXd>& points,
                               const std::vector<PushAssignment>& pushers) {
  std::vector<PushLeg> legs;
  for (size_t j = 0; j + 1 < points.size(); ++j) {
    std::vector<bool> busy(task.scene.bodies().size(), true);
    for (const PushAssignment& push : pushers) busy[push.pusher] = false;
    PushLeg leg{pushed, points[j], points[j + 1], 0.0, 0.0, {}};
    leg.pushes = placePushers(task, pairs, pushed, leg.from, leg.to, busy);
    if (leg.pushes.size() != pushers.size()) return {};
    legs.push_back(std::move(leg));
  }
  return legs;
}

/// The control effort of a leg (the summed squared displacement of its pushers' controls): a
/// pusher's control is its velocity minus the reaction 2 offset lambda, with the impulses
/// (lambda times the leg's duration) that move the body by the leg, G impulse = to - from (G's
/// columns grad_{p_pushed} c = -2 offset).
double legEffort(const PushLeg& leg) {
  Eigen::MatrixXd G(leg.from.size(), leg.pushes.size());
  for (size_t k = 0; k < leg.pushes.size(); ++k) G.col(k) = -2.0 * leg.pushes[k].offset;
  const Eigen::VectorXd impulse = nonnegativeLeastSquares(G, leg.to - leg.from);
  double effort = 0.0;
  for (size_t k = 0; k < leg.pushes.size(); ++k) {
    effort += (leg.to - leg.from - 2.0 * leg.pushes[k].offset * impulse(k)).squaredNorm();
  }
  return effort;
}

/// One pushed body's plan between contact and release: its legs, and between them its pushers'
/// transits round it, each of a duration of least effort within the push phase.
struct BodyPush {
  std::vector<PushLeg> legs;
  /// transits[j][k]: pusher k of the legs from its pose in leg j to its pose in leg j + 1.
  std::vector<std::vector<std::vector<Eigen::VectorXd>>> turns;

  double effort() const {
    double total = 0.0;
    for (double e : pieceEfforts()) total += e;
    return total;
  }
  /// Leg 0, turn 0, leg 1, ...
  std::vector<double> pieceEfforts() const {
    std::vector<double> efforts;
    for (size_t j = 0; j < legs.size(); ++j) {
      efforts.push_back(legEffort(legs[j]));
      if (j >= turns.size()) continue;
      double turn = 0.0;
      for (const std::vector<Eigen::VectorXd>& path : turns[j]) turn += squaredLength(path);
      efforts.push_back(turn);
    }
    return efforts;
  }
};

BodyPush planBodyPush(const SceneTask& task, const std::vector<ContactPair>& pairs, int pushed,
                      const Eigen::VectorXd& end, const std::vector<PushAssignment>& pushers,
                      const std::vector<Eigen::VectorXd>& rest) {
  const Scene& scene = task.scene;
  const Eigen::VectorXd start = scene.bodies()[pushed].position;
  BodyPush push;
  double pusher_radius = 0.0;
  for (const PushAssignment& p : pushers) {
    pusher_radius = std::max(pusher_radius, scene.bodies()[p.pusher].radius);
  }
  const std::vector<Eigen::VectorXd> points = legPoints(task, pushed, end, pusher_radius);
  if (points.size() > 2) push.legs = legsAlong(task, pairs, pushed, points, pushers);
  if (push.legs.empty()) {
    push.legs = {{pushed, start, end, 0.0, 0.0, pushers}};
    return push;
  }
  std::vector<Eigen::VectorXd> resting = rest;
  for (size_t j = 0; j + 1 < push.legs.size(); ++j) {
    const Eigen::VectorXd at = push.legs[j].to;
    resting[pushed] = at;
    std::vector<std::vector<Eigen::VectorXd>> turn;
    for (size_t k = 0; k < pushers.size(); ++k) {
      turn.push_back(transitPath(task, pushers[k].pusher, at + push.legs[j].pushes[k].offset,
                                 at + push.legs[j + 1].pushes[k].offset, resting, pushed));
    }
    push.turns.push_back(std::move(turn));
  }
  return push;
}

/// Times the pieces of a body's push within [begin, end] by least effort (durations ~ the roots
/// of their efforts) and adds its legs and turns to the plan.
void schedule(const BodyPush& push, double begin, double end, PushPlan& plan) {
  const std::vector<double> efforts = push.pieceEfforts();
  double total = 0.0;
  for (double e : efforts) total += std::sqrt(e);
  double t = begin;
  for (size_t piece = 0; piece < efforts.size(); ++piece) {
    const double next = piece + 1 == efforts.size() ? end
                        : total > 0.0 ? t + (end - begin) * std::sqrt(efforts[piece]) / total
                                      : t + (end - begin) / efforts.size();
    if (piece % 2 == 0) {
      PushLeg leg = push.legs[piece / 2];
      leg.begin = t;
      leg.end = next;
      plan.legs.push_back(std::move(leg));
    } else {
      const PushLeg& before = push.legs[piece / 2];
      for (size_t k = 0; k < before.pushes.size(); ++k) {
        plan.transits.push_back({before.pushes[k].pusher, t, next, push.turns[piece / 2][k]});
      }
    }
    t = next;
  }
}

}  // namespace

PushPlan planPushes(const SceneTask& task, const std::vector<ContactPair>& pairs) {
  const Scene& scene = task.scene;
  const int count = static_cast<int>(scene.bodies().size());
  PushPlan plan;
  SceneTask planned = task;  // with the pushed bodies' ends the pushers can reach
  std::vector<bool> busy(count, false);
  std::vector<Eigen::VectorXd> starts, ends;
  for (const SceneBody& body : scene.bodies()) starts.push_back(body.position);
  ends = starts;
  std::vector<BodyPush> pushes(count);
  for (int b = 0; b < count; ++b) {
    const BodyTask& t = task.bodies[b];
    if (scene.bodies()[b].actuated || !hasGoal(t) || (t.target - starts[b]).norm() == 0.0) {
      continue;
    }
    const PushPlan::ShortPush short_push = pushableEnd(task, pairs, b, busy);
    const Eigen::VectorXd end = short_push.end;
    if (end != t.target) plan.short_pushes.push_back(short_push);
    planned.bodies[b].target = end;
    if (end == starts[b]) continue;  // no push: no direction to push from
    const std::vector<PushAssignment> pushers = placePushers(task, pairs, b, starts[b], end, busy);
    if (pushers.empty()) continue;
    ends[b] = end;
    pushes[b] = planBodyPush(task, pairs, b, end, pushers, starts);
    const std::vector<PushAssignment>& first = pushes[b].legs.front().pushes;
    plan.pushes.insert(plan.pushes.end(), first.begin(), first.end());
  }

  // Each pusher's approach (to its first pose, the others resting at their starts); actuated
  // bodies without a push go to their targets over the horizon.
  std::vector<std::vector<Eigen::VectorXd>> approach(count);
  double approach_effort = 0.0, push_effort = 0.0, back_effort = 0.0;
  for (const BodyPush& push : pushes) {
    if (push.legs.empty()) continue;
    push_effort += push.effort();
    const PushLeg& first = push.legs.front();
    for (const PushAssignment& p : first.pushes) {
      approach[p.pusher] =
          transitPath(task, p.pusher, starts[p.pusher], first.from + p.offset, starts, p.pushed);
      approach_effort += squaredLength(approach[p.pusher]);
    }
  }
  // Their returns from the last pose to their targets, straight for the phase times; their
  // paths round the bodies where the push left them follow once the push is simulated.
  for (const BodyPush& push : pushes) {
    if (push.legs.empty()) continue;
    const PushLeg& last = push.legs.back();
    for (const PushAssignment& p : last.pushes) {
      const BodyTask& t = task.bodies[p.pusher];
      if (hasGoal(t)) back_effort += (t.target - last.to - p.offset).squaredNorm();
    }
  }
  // Phase lengths of least control effort: with straight, uniform motion a phase of length tau
  // costs c / tau, c = the sum of the pushers' squared (control x tau), so tau ~ sqrt(c).
  const double total = std::sqrt(approach_effort) + std::sqrt(push_effort) + std::sqrt(back_effort);
  plan.contact_time = plan.release_time = task.horizon;
  if (!plan.pushes.empty() && total > 0.0) {
    plan.contact_time = task.horizon * std::sqrt(approach_effort) / total;
    plan.release_time =
        task.horizon * (std::sqrt(approach_effort) + std::sqrt(push_effort)) / total;
    // No phase shorter than the speed bounds allow (a push to the edge of what time allows).
    const PushTimes least = leastPhaseTimes(planned, plan.pushes);
    plan.contact_time = std::min(std::max(plan.contact_time, least.approach), task.horizon);
    plan.release_time =
        std::min(std::max(plan.release_time, plan.contact_time + least.push), task.horizon);
  }
  for (int b = 0; b < count; ++b) {
    if (!scene.bodies()[b].actuated) {
      if (!pushes[b].legs.empty()) schedule(pushes[b], plan.contact_time, plan.release_time, plan);
    } else if (!approach[b].empty()) {
      plan.transits.push_back({b, 0.0, plan.contact_time, approach[b]});
    } else if (hasGoal(task.bodies[b])) {
      plan.transits.push_back({b, 0.0, task.horizon,
                               transitPath(task, b, starts[b], task.bodies[b].target, starts, -1)});
    }
  }
  if (back_effort > 0.0) {
    const PlannedMotion pushed(planned, pairs, plan.legs, plan.transits);
    const Eigen::VectorXd released = pushed.state(plan.release_time);
    std::vector<Eigen::VectorXd> rest;
    for (int b = 0; b < count; ++b) rest.push_back(scene.position(b, released));
    for (const BodyPush& push : pushes) {
      if (push.legs.empty()) continue;
      const PushLeg& last = push.legs.back();
      for (const PushAssignment& p : last.pushes) {
        if (!hasGoal(task.bodies[p.pusher])) continue;
        plan.transits.push_back({p.pusher, plan.release_time, task.horizon,
                                 transitPath(task, p.pusher, last.to + p.offset,
                                             task.bodies[p.pusher].target, rest, p.pushed)});
      }
    }
  }
  std::stable_sort(plan.transits.begin(), plan.transits.end(),
                   [](const Transit& a, const Transit& b) {
                     return a.body < b.body || (a.body == b.body && a.begin < b.begin);
                   });
  const auto motion =
      std::make_shared<const PlannedMotion>(planned, pairs, plan.legs, plan.transits);
  plan.guess.state = [motion](double t) { return motion->state(t); };
  plan.guess.multipliers = [motion](double t) { return motion->multipliers(t); };
  plan.guess.switch_times = motion->contactOnsets();
  for (int k = 0; k < task.num_intervals; ++k) {
    plan.guess.controls.push_back(motion->meanControl(task.horizon * k / task.num_intervals,
                                                      task.horizon * (k + 1) / task.num_intervals));
  }
  return plan;
}

}  // namespace fesd
