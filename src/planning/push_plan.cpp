#include "fesd_trajopt/planning/push_plan.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <memory>
#include <stdexcept>

#include "fesd_trajopt/planning/bounding_discs.h"
#include "fesd_trajopt/planning/paths_around.h"
#include "fesd_trajopt/planning/planned_motion.h"
#include "fesd_trajopt/planning/pusher_poses.h"
#include "fesd_trajopt/planning/turning_push.h"
#include "fesd_trajopt/scene/pair_check.h"

namespace fesd {
namespace {

/// Transits keep this fraction of a pair's size from what they go round, and turns of legs leave
/// that much more room: within the lazy pairs' margin, so that the pairs a plan passes are
/// modelled from the first round.
constexpr double kClearance = 0.05;
/// A straight transit into (or out of) the body it arrives at (or leaves) in contact may cut
/// into its contact circle down to this fraction of the contact distance: the planned motion
/// slides it along the rim into place, which the plans keep as a contact. One that would cut
/// deeper goes round the body, clear of it, and arrives along the line of centres.
constexpr double kTouchedFraction = 0.8;

/// Turning points of a body of radius `room` (around its centre) inside its workspace and at
/// least `room` from every wall.
std::function<bool(const Eigen::Vector2d&)> roomFor(const SceneTask& task, int body, double room) {
  return [&task, body, room](const Eigen::Vector2d& p) {
    for (const SceneWall& wall : task.scene.walls()) {
      if (wall.normal.head<2>().dot(p) - wall.offset < room) return false;
    }
    return task.bodies[body].insideWorkspace(p);
  };
}

std::vector<Eigen::VectorXd> inScene(const std::vector<Eigen::Vector2d>& path) {
  return std::vector<Eigen::VectorXd>(path.begin(), path.end());
}

/// An actuated body's path from `from` to `to` round the obstacles and the bodies at rest (`rest`:
/// their positions meanwhile; empty for bodies that move on their own), keeping their clearance.
/// `touched` (-1: none), the body it arrives at or leaves in contact, only as far as
/// kTouchedFraction of the contact distance on a straight path; a path that must go round it
/// keeps the clearance from it too and arrives (leaves) along the line of centres: going round
/// on the rim (the planned motion projects the pusher onto the contact circle) left plans that
/// graze the body between stage points. Straight in space.
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
  const bool touches = touched >= 0 && rest[touched].size() > 0;
  for (size_t b = 0; b < scene.bodies().size(); ++b) {
    if (static_cast<int>(b) == body || rest[b].size() == 0) continue;
    const double contact = scene.bodies()[b].radius + radius;
    const double distance =
        static_cast<int>(b) == touched ? kTouchedFraction * contact : (1.0 + kClearance) * contact;
    query.keep_out.push_back({rest[b], distance, (1.0 + kClearance) * contact});
  }
  query.allowed = roomFor(task, body, (1.0 + kClearance) * radius);
  std::vector<Eigen::VectorXd> path = inScene(pathAround(query));
  if (!touches || path.size() == 2) return path;
  // Round the touched body: clear of it, and in and out along the line of centres.
  const Eigen::Vector2d centre = rest[touched];
  const double contact = scene.bodies()[touched].radius + radius;
  const auto clear_of_touched = [&](const Eigen::VectorXd& at) -> Eigen::Vector2d {
    const Eigen::Vector2d out = Eigen::Vector2d(at) - centre;
    if (out.norm() > (1.0 + 0.5 * kClearance) * contact || out.norm() == 0.0) return at;
    return centre + (1.0 + kClearance) * contact * out.normalized();
  };
  for (KeepOut& keep_out : query.keep_out) {
    if (keep_out.centre == centre) keep_out.distance = keep_out.corner;
  }
  query.from = clear_of_touched(from);
  query.to = clear_of_touched(to);
  path = inScene(pathAround(query));
  if (Eigen::VectorXd(query.from) != from) path.insert(path.begin(), from);
  if (Eigen::VectorXd(query.to) != to) path.push_back(to);
  return path;
}

/// The turning points of a pushed body's legs from its start to `end`: round the obstacles (as
/// near as touching: a straight push that grazes a post is still the push to plan), its pusher
/// (radius `pusher_radius`, straight behind it) clear of them too along each leg; fewer legs win
/// near ties (a leg costs a heuristic pi (R + r_pusher), about a pusher's way half round the body).
/// Passive bodies on the way are shoved (going round them through clutter cost the solver up to 40
/// times the iterations on the cluttered sweep). Without such legs the push is straight. Straight
/// in space.
std::vector<Eigen::VectorXd> legPoints(const SceneTask& task, int pushed,
                                       const Eigen::VectorXd& end, double pusher_radius) {
  const Scene& scene = task.scene;
  const Eigen::VectorXd start = scene.bodies()[pushed].position;
  if (scene.dimension() != 2) return {start, end};
  const double radius = scene.bodies()[pushed].radius;
  std::vector<std::pair<Eigen::Vector2d, double>> fixed;  // centre, radius of each obstacle
  for (const SceneObstacle& obstacle : scene.obstacles()) {
    fixed.push_back({obstacle.position, obstacle.radius});
  }
  PathQuery query;
  query.from = start;
  query.to = end;
  for (const auto& [centre, r] : fixed) {
    query.keep_out.push_back({centre, r + radius, (1.0 + kClearance) * (r + radius)});
  }
  query.passable = [fixed, behind = radius + pusher_radius, pusher_radius](
                       const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
    const Eigen::Vector2d back = -behind * (b - a).normalized();
    return std::all_of(fixed.begin(), fixed.end(), [&](const auto& disc) {
      return segmentDistance(disc.first, Eigen::VectorXd(a + back), Eigen::VectorXd(b + back)) >=
             disc.second + pusher_radius;
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
  if (path.size() == 2) return (path[1] - path[0]).squaredNorm();
  const double length = pathLength(path);
  return length * length;
}

/// The impulses (lambda times the push's duration) with which the pushers move their body by
/// `displacement`: G impulse = displacement, G's columns grad_{p_pushed} c = -2 offset, >= 0.
Eigen::VectorXd pushImpulses(const std::vector<PushAssignment>& pushes,
                             const Eigen::VectorXd& displacement) {
  Eigen::MatrixXd G(displacement.size(), pushes.size());
  for (size_t k = 0; k < pushes.size(); ++k) G.col(k) = -2.0 * pushes[k].offset;
  return nonnegativeLeastSquares(G, displacement);
}

/// The control effort of a push (the summed squared displacement of its pushers' controls): a
/// pusher's control is its velocity minus the reaction 2 offset lambda (pushImpulses). A turning
/// push counts as straight along its first direction for its length: its pushers turn with it.
double pushEffort(const std::vector<PushAssignment>& pushes, const Eigen::VectorXd& displacement) {
  const Eigen::VectorXd impulse = pushImpulses(pushes, displacement);
  double effort = 0.0;
  for (size_t k = 0; k < pushes.size(); ++k) {
    effort += (displacement - 2.0 * pushes[k].offset * impulse(k)).squaredNorm();
  }
  return effort;
}

/// The pushers whose force the push needs (a positive impulse in pushEffort's sense); the others
/// are free again. A pusher tilted far from straight behind, beside one straight behind, adds
/// nothing but a body to carry along.
std::vector<PushAssignment> contributing(const std::vector<PushAssignment>& pushers,
                                         const Eigen::VectorXd& displacement,
                                         std::vector<bool>& busy) {
  const Eigen::VectorXd impulse = pushImpulses(pushers, displacement);
  std::vector<PushAssignment> needed;
  for (size_t k = 0; k < pushers.size(); ++k) {
    if (impulse(k) > 0.0) {
      needed.push_back(pushers[k]);
    } else {
      busy[pushers[k].pusher] = false;
    }
  }
  return needed;
}

/// The push of one body from its start to `end` by `pushers` (placed for the straight push):
/// straight, or in legs round the obstacles (legPoints) when the straight push is not passable,
/// its corners rounded by the pushed body's and its largest pusher's radii, the same pushers
/// placed anew behind its first leg; straight when one of them finds no pose there.
PushLeg planBodyPush(const SceneTask& task, const std::vector<ContactPair>& pairs, int pushed,
                     const Eigen::VectorXd& end, const std::vector<PushAssignment>& pushers) {
  const Scene& scene = task.scene;
  PushLeg leg{pushed, scene.bodies()[pushed].position, end, 0.0, 0.0, pushers, {}, 0.0};
  double pusher_radius = 0.0;
  for (const PushAssignment& p : pushers) {
    pusher_radius = std::max(pusher_radius, scene.bodies()[p.pusher].radius);
  }
  const std::vector<Eigen::VectorXd> points = legPoints(task, pushed, end, pusher_radius);
  if (points.size() == 2) return leg;
  std::vector<bool> busy(scene.bodies().size(), true);
  for (const PushAssignment& push : pushers) busy[push.pusher] = false;
  std::vector<PushAssignment> behind_first =
      placePushers(task, pairs, pushed, points[0], points[1], busy);
  if (behind_first.size() != pushers.size()) return leg;
  leg.pushes = std::move(behind_first);
  leg.through.assign(points.begin() + 1, points.end() - 1);
  leg.turn_radius = scene.bodies()[pushed].radius + pusher_radius;
  return leg;
}

}  // namespace

std::vector<Eigen::VectorXd> pushCorners(const PushLeg& leg) {
  std::vector<Eigen::VectorXd> corners{leg.from};
  corners.insert(corners.end(), leg.through.begin(), leg.through.end());
  corners.push_back(leg.to);
  return corners;
}

RoundedPath roundedPush(const PushLeg& leg) {
  if (leg.from.size() != 2) throw std::invalid_argument("roundedPush: a push with turns is planar");
  const std::vector<Eigen::VectorXd> corners = pushCorners(leg);
  return RoundedPath(std::vector<Eigen::Vector2d>(corners.begin(), corners.end()), leg.turn_radius);
}

Eigen::VectorXd endOffset(const PushLeg& leg, size_t k) {
  const Eigen::VectorXd& offset = leg.pushes[k].offset;
  if (leg.through.empty()) return offset;
  if (offset.size() != 2) throw std::invalid_argument("endOffset: a push with turns is planar");
  const Eigen::Vector2d first = leg.through.front() - leg.from, last = leg.to - leg.through.back();
  return Eigen::Rotation2Dd(signedAngle(first, last)) * Eigen::Vector2d(offset);
}

PushPlan planPushes(const SceneTask& task, const std::vector<ContactPair>& pairs) {
  if (std::optional<PushPlan> turning = planTurningPush(task, pairs)) return *std::move(turning);
  if (hasCompositeBodies(task.scene)) {
    const BoundingDiscPairs discs = boundingDiscPairs(task.scene, pairs);
    PushPlan plan = planPushes(boundingDiscTask(task), discs.pairs);
    plan.guess = guessOfSpheres(task, pairs, discs, plan.guess);
    return plan;
  }
  const Scene& scene = task.scene;
  const int count = static_cast<int>(scene.bodies().size());
  PushPlan plan;
  SceneTask planned = task;  // with the pushed bodies' ends the pushers can reach
  std::vector<bool> busy(count, false);
  std::vector<Eigen::VectorXd> starts;
  for (const SceneBody& body : scene.bodies()) starts.push_back(body.position);
  std::vector<std::vector<PushAssignment>> pushers(count);
  for (int b = 0; b < count; ++b) {
    const BodyTask& t = task.bodies[b];
    if (scene.bodies()[b].actuated || !t.hasTarget() || (t.target - starts[b]).norm() == 0.0) {
      continue;
    }
    const PushPlan::ShortPush short_push = pushableEnd(task, pairs, b, busy);
    const Eigen::VectorXd end = short_push.end;
    if (end != t.target) plan.short_pushes.push_back(short_push);
    planned.bodies[b].target = end;
    if (end == starts[b]) continue;  // no push: no direction to push from
    pushers[b] =
        contributing(placePushers(task, pairs, b, starts[b], end, busy), end - starts[b], busy);
  }
  // Bodies at rest unless pushed: the passive ones and the actuators without a target that push
  // nothing.
  const auto atRest = [&](std::vector<Eigen::VectorXd> positions) {
    for (int b = 0; b < count; ++b) {
      if (scene.bodies()[b].actuated && (task.bodies[b].hasTarget() || busy[b]))
        positions[b].resize(0);
    }
    return positions;
  };
  const std::vector<Eigen::VectorXd> at_start = atRest(starts);
  std::vector<PushLeg> pushes;
  for (int b = 0; b < count; ++b) {
    if (pushers[b].empty()) continue;
    pushes.push_back(planBodyPush(task, pairs, b, planned.bodies[b].target, pushers[b]));
    plan.pushes.insert(plan.pushes.end(), pushes.back().pushes.begin(), pushes.back().pushes.end());
  }

  // Each pusher's approach (to its pose, the others resting at their starts).
  std::vector<std::vector<Eigen::VectorXd>> approach(count);
  double approach_effort = 0.0, push_effort = 0.0, back_effort = 0.0;
  for (const PushLeg& push : pushes) {
    const std::vector<Eigen::VectorXd> corners = pushCorners(push);
    const Eigen::VectorXd displacement =
        corners.size() == 2
            ? Eigen::VectorXd(push.to - push.from)
            : Eigen::VectorXd(pathLength(corners) * (corners[1] - push.from).normalized());
    push_effort += pushEffort(push.pushes, displacement);
    for (const PushAssignment& p : push.pushes) {
      approach[p.pusher] =
          transitPath(task, p.pusher, starts[p.pusher], push.from + p.offset, at_start, p.pushed);
      approach_effort += squaredLength(approach[p.pusher]);
    }
  }
  // Their returns from their last poses to their targets, straight for the phase times; their
  // paths round the bodies where the push left them follow once the push is simulated.
  for (const PushLeg& push : pushes) {
    for (size_t k = 0; k < push.pushes.size(); ++k) {
      const BodyTask& t = task.bodies[push.pushes[k].pusher];
      if (t.hasTarget()) back_effort += (t.target - push.to - endOffset(push, k)).squaredNorm();
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
  for (PushLeg& push : pushes) {
    push.begin = plan.contact_time;
    push.end = plan.release_time;
    plan.legs.push_back(push);
  }
  for (int b = 0; b < count; ++b) {
    if (!scene.bodies()[b].actuated) continue;
    if (!approach[b].empty()) {
      plan.transits.push_back({b, 0.0, plan.contact_time, approach[b]});
    } else if (task.bodies[b].hasTarget()) {
      // Actuated bodies without a push go to their targets over the horizon.
      plan.transits.push_back(
          {b, 0.0, task.horizon,
           transitPath(task, b, starts[b], task.bodies[b].target, at_start, -1)});
    }
  }
  if (back_effort > 0.0) {
    const PlannedMotion pushed(planned, pairs, plan.legs, plan.transits);
    const Eigen::VectorXd released = pushed.state(plan.release_time);
    std::vector<Eigen::VectorXd> released_at;
    for (int b = 0; b < count; ++b) released_at.push_back(scene.position(b, released));
    const std::vector<Eigen::VectorXd> rest = atRest(released_at);
    for (const PushLeg& push : plan.legs) {
      for (size_t k = 0; k < push.pushes.size(); ++k) {
        const int pusher = push.pushes[k].pusher;
        if (!task.bodies[pusher].hasTarget()) continue;
        plan.transits.push_back({pusher, plan.release_time, task.horizon,
                                 transitPath(task, pusher, push.to + endOffset(push, k),
                                             task.bodies[pusher].target, rest, push.pushed)});
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
  for (int k = 0; k < task.num_intervals; ++k) {
    plan.guess.controls.push_back(motion->meanControl(task.horizon * k / task.num_intervals,
                                                      task.horizon * (k + 1) / task.num_intervals));
  }
  return plan;
}

}  // namespace fesd
