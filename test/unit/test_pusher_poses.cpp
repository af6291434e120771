// Pusher poses and reach (planning/pusher_poses.cpp): the nonnegative fit, pair lookup, poses
// behind a push within workspaces (tilted when straight behind is out of bounds, busy pushers
// left out), the shortest push the speed bounds allow, and the end a push can reach.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/planning/pusher_poses.h"
#include "support/scene_tasks.h"

namespace {

TEST(PusherPoses, TheNonnegativeFitDropsWhatWouldPull) {
  // Unconstrained least squares would take lambda_2 = -1: the fit keeps only the first column.
  const Eigen::Matrix2d G = Eigen::Matrix2d::Identity();
  const Eigen::VectorXd lambda = fesd::nonnegativeLeastSquares(G, Eigen::Vector2d(1.0, -1.0));
  EXPECT_DOUBLE_EQ(lambda(0), 1.0);
  EXPECT_DOUBLE_EQ(lambda(1), 0.0);
  Eigen::MatrixXd H(2, 2);
  H << 1.0, 1.0, 0.0, 1.0;
  EXPECT_LT(
      (fesd::nonnegativeLeastSquares(H, Eigen::Vector2d(3.0, 2.0)) - Eigen::Vector2d(1, 2)).norm(),
      1e-12);
}

TEST(PusherPoses, BodyPairsAreFoundInEitherOrder) {
  const std::vector<fesd::ContactPair> pairs{{0, fesd::ContactPair::Kind::kObstacle, 1},
                                             {2, fesd::ContactPair::Kind::kBody, 0}};
  EXPECT_EQ(fesd::bodyPairIndex(pairs, 0, 2), 1);
  EXPECT_EQ(fesd::bodyPairIndex(pairs, 2, 0), 1);
  EXPECT_EQ(fesd::bodyPairIndex(pairs, 0, 1), -1);  // an obstacle, not a body
}

TEST(PusherPoses, APusherSitsStraightBehindUnlessItsWorkspaceForbids) {
  fesd::SceneTask task = fesd_test::pushAlongX();
  const std::vector<fesd::ContactPair> pairs = task.scene.allPairs();
  const Eigen::Vector2d from(0, 0), to(3, 0);
  std::vector<bool> busy(2, false);
  const std::vector<fesd::PushAssignment> straight =
      fesd::placePushers(task, pairs, 1, from, to, busy);
  ASSERT_EQ(straight.size(), 1u);
  EXPECT_LT((straight[0].offset - Eigen::Vector2d(-1, 0)).norm(), 1e-12);
  EXPECT_TRUE(busy[0]);
  // Busy pushers are not placed again.
  EXPECT_TRUE(fesd::placePushers(task, pairs, 1, from, to, busy).empty());
  // y <= -0.5: the pose tilts until it fits, on the contact circle of radius 1.
  task.bodies[0].workspace_upper = Eigen::Vector2d(10.0, -0.5);
  task.bodies[0].workspace_lower = Eigen::Vector2d(-10.0, -10.0);
  std::vector<bool> free(2, false);
  const std::vector<fesd::PushAssignment> tilted =
      fesd::placePushers(task, pairs, 1, from, to, free);
  ASSERT_EQ(tilted.size(), 1u);
  EXPECT_NEAR(tilted[0].offset.norm(), 1.0, 1e-12);
  EXPECT_LE(tilted[0].offset.y(), -0.5);
  EXPECT_NEAR(tilted[0].offset.y(), -0.5, 0.02);  // within one 1-degree step
  // Without a pair between them no pose is placed.
  std::vector<bool> again(2, false);
  EXPECT_TRUE(fesd::placePushers(task, {}, 1, from, to, again).empty());
}

TEST(PusherPoses, APusherKeepsClearOfWallsAndABodyEndsAgainstTheWallItCannotBePushedAlong) {
  const fesd::SceneTask task = fesd_test::pushAlongAWall();
  const std::vector<fesd::ContactPair> pairs = task.scene.allPairs();
  std::vector<bool> busy(2, false);
  // Straight behind the puck the pusher would cut 0.15 into the wall: it tilts away from it.
  const std::vector<fesd::PushAssignment> placed =
      fesd::placePushers(task, pairs, 1, Eigen::Vector2d(0, 0), Eigen::Vector2d(3, 0), busy);
  ASSERT_EQ(placed.size(), 1u);
  EXPECT_GE(placed[0].offset.y(), 0.15);
  EXPECT_LT(placed[0].offset.y(), 0.15 + 0.8 * std::sin(M_PI / 180.0));
  // So the target, 0.05 off the wall, is out of reach: the puck ends against the wall below it.
  const fesd::PushPlan::ShortPush end = fesd::pushableEnd(task, pairs, 1, {false, false});
  EXPECT_FALSE(end.time_limited);
  EXPECT_LT((end.end - Eigen::Vector2d(3.0, -0.05)).norm(), 1e-12);
}

TEST(PusherPoses, TheShortestPushGoesAtTheSpeedBoundsAndSharesThePush) {
  // pushingTask: the pusher (|u_d| <= 2) 2 from its pose behind the puck; one pusher moves the
  // puck at half its speed.
  const fesd::SceneTask task = fesd_test::pushingTask();
  const std::vector<fesd::PushAssignment> pushers{{0, 1, Eigen::Vector2d(-1.0, 0.0)}};
  const fesd::PushTimes times =
      fesd::shortestPush(task, pushers, Eigen::Vector2d(0, 0), Eigen::Vector2d(1.5, 0));
  EXPECT_DOUBLE_EQ(times.approach, 1.0);
  EXPECT_DOUBLE_EQ(times.push, 1.5);
  const fesd::PushTimes none =
      fesd::shortestPush(task, {}, Eigen::Vector2d(0, 0), Eigen::Vector2d(1.5, 0));
  EXPECT_TRUE(std::isinf(none.push));
}

TEST(PusherPoses, APushableTargetIsItsOwnEndAndOneInAnObstacleIsMovedClear) {
  fesd::SceneTask task = fesd_test::pushAlongX();
  const std::vector<bool> busy(2, false);
  const fesd::PushPlan::ShortPush own = fesd::pushableEnd(task, task.scene.allPairs(), 1, busy);
  EXPECT_EQ(own.end, task.bodies[1].target);
  task.scene.obstacles() = {{"rock", 0.5, Eigen::Vector2d(3.2, 0.0)}};
  const fesd::PushPlan::ShortPush moved = fesd::pushableEnd(task, task.scene.allPairs(), 1, busy);
  EXPECT_FALSE(moved.time_limited);
  const double clearance = (moved.end - Eigen::Vector2d(3.2, 0.0)).norm();
  EXPECT_GE(clearance, 1.0);  // the puck's radius plus the rock's
  EXPECT_LT(clearance, 1.0 + 0.1);
}

}  // namespace
