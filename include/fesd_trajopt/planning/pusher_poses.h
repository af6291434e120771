#pragma once

#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/planning/push_plan.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace fesd {

/// lambda >= 0 minimising |G lambda - v| (active set: drop the most negative and solve again).
Eigen::VectorXd nonnegativeLeastSquares(const Eigen::MatrixXd& G, const Eigen::VectorXd& v);

/// The index in `pairs` of the pair of bodies a and b (either order), -1 if there is none.
int bodyPairIndex(const std::vector<ContactPair>& pairs, int a, int b);

/// The pushers of a passive body pushed straight from `from` to `to`, placed in index order:
/// each actuated body that is not `busy` and has a pair with it in `pairs`, at the pose most
/// directly behind the push (tilted in steps of 1 degree up to 89) inside its workspace and
/// clear of the walls at both ends, clear of the obstacles at the start (a push may go round
/// them in legs), and apart from those placed before it. The placed ones become busy.
std::vector<PushAssignment> placePushers(const SceneTask& task,
                                         const std::vector<ContactPair>& pairs, int pushed,
                                         const Eigen::VectorXd& from, const Eigen::VectorXd& to,
                                         std::vector<bool>& busy);

/// The shortest approach and push phases the speed bounds allow, judged optimistically (the
/// nearest pusher straight to its pose at full speed; k pushers move a passive body at
/// k / (k + 1) of the fastest one's speed); infinite when no pusher can move.
struct PushTimes {
  double approach = 0.0, push = 0.0;
};
PushTimes shortestPush(const SceneTask& task, const std::vector<PushAssignment>& pushers,
                       const Eigen::VectorXd& start, const Eigen::VectorXd& end);

/// The longest shortestPush over the pushed bodies of `pushes` (to their targets in `planned`),
/// so that a push judged in time keeps a push phase.
PushTimes leastPhaseTimes(const SceneTask& planned, const std::vector<PushAssignment>& pushes);

/// Where the plan pushes a passive body: its target when pushers can be placed to push it there
/// straight (workspace bounds), in time (shortestPush within the horizon) and it ends clear of
/// obstacles and walls; else, when only time rules it out, as far towards it as time allows
/// (time_limited); else the nearest end that is pushable with a straight path clear of obstacles,
/// on rings around the target 2 % of the push's length apart, refined by bisection (the start
/// if none is). Returned as a short push (the target itself when it is pushable).
PushPlan::ShortPush pushableEnd(const SceneTask& task, const std::vector<ContactPair>& pairs,
                                int pushed, const std::vector<bool>& busy);

}  // namespace fesd
