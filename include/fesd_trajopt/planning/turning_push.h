#pragma once

#include <optional>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/planning/push_plan.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// Where a pusher of radius r_P touches a turning body to push it along n (in the body's frame):
/// behind sphere k, its centre at o_k - (r_k + r_P) n, reached from behind without touching the
/// other spheres; the push turns the body at the path curvature lever / rho^2 (lever = o_k x n,
/// counter-clockwise positive: the projection in the metric diag(1, 1, rho^2)).
struct PushContact {
  int sphere = -1;
  Eigen::Vector2d pusher;  ///< the pusher's centre in the body's frame
  double lever = 0.0;
};

/// The contacts from which a pusher of `pusher_radius` can push `body` along n (body frame).
std::vector<PushContact> pushContacts(const SceneBody& body, double pusher_radius,
                                      const Eigen::Vector2d& n);

/// One pusher bringing one turning body to a pose. A push with its contact fixed on the body
/// moves it along an arc (curvature lever / rho^2) whose tangent turns with the body: the push
/// direction stays fixed in the body's frame. The plan is a push along such an arc behind the
/// sphere whose lever gives its curvature, between straight pushes along the arc's tangents
/// (either or both of no length), or an arc and a straight push to the target in either order;
/// a straight push stands behind the sphere of least lever. Between pushes the body rests while
/// the pusher goes round its spheres to the next contact. The cheapest over the start headings
/// (every degree) and arc spheres wins: length, plus how far the straight pushes' lever would
/// turn the body, plus the pusher's ways between pushes. The pusher gets to its first contact
/// round the body's spheres; the phases share the horizon by the pusher's command each needs
/// (the least effort at the speed bound); the multiplier of the pushing contact is the one that
/// moves the body along the plan (its projection on the contact's direction, >= 0), exactly on
/// the arcs.
///
/// Only for a planar scene of one actuated disc without a target and one turning body with a
/// position and a yaw target, nothing else (no obstacles or walls, bounds the plan keeps), whose
/// pusher-sphere pairs are all in `pairs`; otherwise, or when no plan of these shapes reaches the
/// pose within the pusher's speed (a turn of nearly half a circle, a target too far): nothing.
std::optional<PushPlan> planTurningPush(const SceneTask& task,
                                        const std::vector<ContactPair>& pairs);

}  // namespace fesd
