#pragma once

#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/discretization/trajectory_guess.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// An actuated body pushing a passive one: during the push it sits at pushed + offset,
/// |offset| = the sum of their radii, i.e. exactly in contact.
struct PushAssignment {
  int pusher, pushed;  ///< body indices in the task
  Eigen::VectorXd offset;
};

/// A first guess for a scene task's OCP from a plan in three phases shared by all bodies:
/// approach (the pushers move straight to their pushing poses), push (every passive body with a
/// target moves straight to it, its pushers with it), return (the pushers move straight to
/// their own targets). The phase lengths are those of least control effort for this motion
/// (tau_phase ~ the root of the phase's summed squared displacements of control). Bodies
/// without a push move straight to their targets over the horizon, or stay.
///
/// What is in the way: a pushed body's path is moved out of the obstacles and walls it would
/// cross (it slides around them, its pushers with it); the passive bodies without a target move
/// only when pushed, as the projected dynamics move them: whatever pushes into them shoves them
/// along the contact normal, and they shove others in turn (chains), simulated in small time
/// steps. Actuated bodies step around everything they do not push.
///
/// lambda of every pair in contact is the nonnegative least-squares force that moves the passive
/// bodies along their planned paths; the controls are the planned velocities minus the contact
/// reactions. The plan is a deterministic function of the task, so the OCP solved from it is the
/// same on every machine (OcpSolver::solve(guess)).
struct PushPlan {
  /// Where the push phase begins and ends (both the horizon when nothing is pushed).
  double contact_time = 0.0, release_time = 0.0;
  std::vector<PushAssignment> pushes;
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
};

/// Pushers: each actuated body pushes at most one passive body with a target, through a body
/// pair of `pairs`. Its pushing pose is the one most directly behind the push direction
/// (tilted in steps of 1 degree up to 89) that keeps it inside its workspace bounds at the
/// start and end of the push and apart from the pushers placed before it. Only the pairs in
/// `pairs` touch in the plan, and the guess's multipliers are theirs, in that order. A target
/// no placement of pushers can push to is replaced in the plan by the nearest end one can.
PushPlan planPushes(const SceneTask& task, const std::vector<ContactPair>& pairs);

}  // namespace fesd
