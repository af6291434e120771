#pragma once

#include <vector>

#include "fesd_trajopt/discretization/trajectory_guess.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// The sphere that pushes a body, by a fixed rule: among the spheres of the end link (the link
/// group moved by the highest-numbered joint that carries spheres: the tool), the one whose
/// centre at q0 is nearest to the approach point, the point behind the body opposite its push
/// direction at the sum of the radii. Ties go to the lower sphere index. -1 without spheres or
/// without an actuated joint. The guess holds passive joints still (IK's held coordinates).
int pushingSphere(const SceneTask& task, int pushed_body);

/// A deterministic first guess for a robot task:
///  - the pushed body: the first passive free body with a weighted target (none: the robot
///    stays at q0 and moves straight to its joint targets);
///  - planPushes on a disc scene in which the pushing sphere (pushingSphere) is an actuated disc
///    of its radius and the pushed body passive, with the scene's obstacles and walls: the
///    sphere's and the body's paths and the contact multiplier; for a body of spheres that turns
///    to a target yaw on a level support (a table), with nothing else but level walls, the
///    turning push plan in the table's plane (the sphere pushing at the body's height);
///  - damped least-squares IK (sphereInverseKinematics) of the sphere's path at every element
///    boundary, each continued from the one before (the first from q0), then the robot's other
///    spheres moved out of the pushed body with the pusher held (clearOfSpheres); joints linear in
///    between;
///  - controls per interval from the joints' motion, clamped to their speed limits; the
///    multiplier of the pair (pushed body, pushing sphere) from the push plan, 0 for the others.
/// Fixed-size arithmetic only, so the same task gives the same guess on every machine.
struct RobotGuess {
  int pushed_body = -1;
  int pusher_sphere = -1;
  TrajectoryGuess guess;  ///< multipliers per `pairs` of planRobotGuess
  /// The joints at the element boundaries (their times are horizon * k / boundaries.size() - 1).
  std::vector<Eigen::VectorXd> boundary_joints;
  /// The pushed body turns in the guess: a body of spheres with a yaw target on a level
  /// support, planned by the turning push planner in the support's plane (PushPlan::turns_bodies).
  bool turns_bodies = false;
};
RobotGuess planRobotGuess(const SceneTask& task, const std::vector<ContactPair>& pairs,
                          int elements_per_interval);

}  // namespace fesd
