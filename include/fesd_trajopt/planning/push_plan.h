#pragma once

#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/discretization/trajectory_guess.h"
#include "fesd_trajopt/planning/paths_around.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// An actuated body pushing a passive one: during the push it sits at pushed + offset,
/// |offset| = the sum of their radii, i.e. exactly in contact.
struct PushAssignment {
  int pusher, pushed;  ///< body indices in the task
  Eigen::VectorXd offset;
};

/// The push of a body from `from` to `to` during [begin, end]: straight, or along turning points
/// `through` with the corners rounded (RoundedPath, radius `turn_radius`), at constant speed. Its
/// pushers sit at the offsets of `pushes` at the start and turn with the path's tangent.
struct PushLeg {
  int pushed;
  Eigen::VectorXd from, to;
  double begin, end;
  std::vector<PushAssignment> pushes;
  std::vector<Eigen::VectorXd> through;
  double turn_radius = 0.0;
};

/// A push's turning points from its start to its end (from, through..., to).
std::vector<Eigen::VectorXd> pushCorners(const PushLeg& leg);
/// The path of a push with turns, its corners rounded by its turn radius (planar pushes only).
RoundedPath roundedPush(const PushLeg& leg);

/// Where pusher k of a push sits relative to the pushed body at the push's end: its offset turned
/// as the path turns from its first direction to its last.
Eigen::VectorXd endOffset(const PushLeg& leg, size_t k);

/// An actuated body's path that touches nothing it does not push: to its pushing pose (the
/// approach), to its own target after the push, or, without a push, from its start to its
/// target. Traversed at constant speed.
struct Transit {
  int body;
  double begin, end;
  std::vector<Eigen::VectorXd> path;  ///< turning points, from start to end
};

/// A first guess for a scene task's OCP from a plan of contacts in three phases shared by all
/// bodies: approach (each pusher goes to its pushing pose), push (every passive body with a
/// target is pushed to it: straight, or round obstacles in straight legs joined by turns in which
/// its pushers turn with it, straight behind), return (the pushers go to their own targets). Phase
/// lengths are those of least control effort for this motion (tau ~ the root of the summed squared
/// displacements of control). Bodies without a push go to their targets over the horizon, or
/// stay.
///
/// What is in the way: in the plane, a pushed body's legs go round the obstacles with its pusher
/// clear of them behind it (pathAround); every transit goes round the obstacles and the bodies at
/// rest. The passive bodies without a
/// target move only when pushed, as the projected dynamics move them: whatever pushes into them
/// shoves them along the contact normal, and they shove others in turn (chains), simulated in
/// small time steps. In space, legs and transits are straight.
///
/// lambda of every pair in contact is the nonnegative least-squares force that moves the passive
/// bodies along their planned paths; the controls are the planned velocities minus the contact
/// reactions. The plan is a deterministic function of the task, so the OCP solved from it is the
/// same on every machine (OcpSolver::solve(guess)).
struct PushPlan {
  /// Where the push phase begins and ends (both the horizon when nothing is pushed).
  double contact_time = 0.0, release_time = 0.0;
  std::vector<PushAssignment> pushes;  ///< of each pushed body, at its push's start
  std::vector<PushLeg> legs;           ///< one push per pushed body, in their order
  std::vector<Transit> transits;       ///< of the actuated bodies, in order of body and time
  /// Pushed bodies whose target the pushers cannot reach (workspace bounds, it lies in an
  /// obstacle, or not within the horizon at their speed bounds): the plan pushes them to the
  /// nearest end they can.
  struct ShortPush {
    int body;
    Eigen::VectorXd end;
    /// Only the time rules the target out: pushing towards it as far as time allows (the end)
    /// is then the best plan for the target itself.
    bool time_limited = false;
  };
  std::vector<ShortPush> short_pushes;
  TrajectoryGuess guess;  ///< of the task's full state; multipliers per pair of planPushes' list
  /// The plan turns the bodies with a target yaw (planTurningPush): the pairs its guess touches
  /// are those the first round needs; otherwise their yaw is left to the NLP.
  bool turns_bodies = false;
};

/// Pushers: each actuated body pushes at most one passive body with a target, through a body
/// pair of `pairs`. Its pushing pose is the one most directly behind the push (tilted in steps of
/// 1 degree up to 89) that keeps it inside its workspace bounds at the start and end of the push
/// (of its first leg, for a push in legs; where the turns take it is not checked) and apart from
/// the pushers placed before it; only pushers whose force the push needs stay. Only
/// the pairs in `pairs` touch in the plan, and the guess's multipliers are theirs, in that order. A
/// target no placement of pushers can push to is replaced in the plan by the nearest end one can.
PushPlan planPushes(const SceneTask& task, const std::vector<ContactPair>& pairs);

}  // namespace fesd
