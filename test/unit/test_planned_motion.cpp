// The planned motion of a push plan (planning/planned_motion.cpp): a leg moves the pushed body
// by the force its pusher carries (also round a corner, the pusher turning behind it), transits
// are followed at constant speed, and a stone in the way is shoved from when the puck meets it.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/planning/planned_motion.h"
#include "support/scene_tasks.h"

namespace {

/// pushAlongX as a plan by hand: the approach from (-2, 0) to (-1, 0) in [0, 0.5], the push of
/// the puck from 0 to 3 in [0.5, 1.5], the pusher at (-1, 0) from the puck.
struct HandPlan {
  fesd::SceneTask task = fesd_test::pushAlongX();
  std::vector<fesd::PushLeg> legs{{1,
                                   Eigen::Vector2d(0, 0),
                                   Eigen::Vector2d(3, 0),
                                   0.5,
                                   1.5,
                                   {{0, 1, Eigen::Vector2d(-1, 0)}},
                                   {},
                                   0.0}};
  std::vector<fesd::Transit> transits{
      {0, 0.0, 0.5, {Eigen::Vector2d(-2, 0), Eigen::Vector2d(-1.5, 0.5), Eigen::Vector2d(-1, 0)}}};
};

TEST(PlannedMotion, ALegMovesThePushedBodyByTheForceItsPusherCarries) {
  HandPlan hand;
  const std::vector<fesd::ContactPair> pairs = hand.task.scene.allPairs();
  const fesd::PlannedMotion motion(hand.task, pairs, hand.legs, hand.transits);
  const Eigen::VectorXd x = motion.state(1.0);
  EXPECT_LT((x.tail<2>() - Eigen::Vector2d(1.5, 0)).norm(), 1e-12);
  EXPECT_LT((x.head<2>() - Eigen::Vector2d(0.5, 0)).norm(), 1e-12);
  // The puck's velocity 3 along x = lambda grad_puck c = lambda 2 (p_puck - p_pusher): lambda 1.5.
  const Eigen::VectorXd lambda = motion.multipliers(1.0);
  ASSERT_EQ(lambda.size(), 1);
  EXPECT_NEAR(lambda(0), 1.5, 1e-6);
  // The pusher's control is its velocity minus the reaction: 3 + 2 * 1.5 = 6 along x.
  const Eigen::VectorXd u = motion.meanControl(0.75, 1.25);
  EXPECT_NEAR(u(0), 6.0, 1e-5);
  EXPECT_NEAR(u(1), 0.0, 1e-9);
}

TEST(PlannedMotion, ThePusherTurnsWithATurningPushAndStillCarriesItsForce) {
  // Round a corner at (1.5, 0) up to (1.5, 1.5), corner radius 1: the pusher stays straight
  // behind the puck along the path's tangent, so the force along the line of centres is the
  // puck's velocity throughout.
  HandPlan hand;
  hand.legs[0].to = Eigen::Vector2d(1.5, 1.5);
  hand.legs[0].through = {Eigen::Vector2d(1.5, 0)};
  hand.legs[0].turn_radius = 1.0;
  const std::vector<fesd::ContactPair> pairs = hand.task.scene.allPairs();
  const fesd::PlannedMotion motion(hand.task, pairs, hand.legs, hand.transits);
  for (double t = 0.55; t < 1.5; t += 0.05) {
    const Eigen::VectorXd x = motion.state(t);
    const double dt = 1e-6;
    const Eigen::Vector2d velocity =
        (motion.state(t + dt).tail<2>() - motion.state(t - dt).tail<2>()) / (2 * dt);
    const Eigen::Vector2d behind = x.tail<2>() - x.head<2>();
    EXPECT_NEAR(behind.norm(), 1.0, 1e-9) << "t = " << t;
    EXPECT_NEAR(behind.normalized().dot(velocity.normalized()), 1.0, 1e-6) << "t = " << t;
    const double lambda = motion.multipliers(t)(0);
    EXPECT_LT((2.0 * lambda * behind - velocity).norm(), 1e-4 * velocity.norm()) << "t = " << t;
  }
  EXPECT_LT((motion.state(1.5).tail<2>() - Eigen::Vector2d(1.5, 1.5)).norm(), 1e-12);
  EXPECT_LT((motion.state(1.5).head<2>() - Eigen::Vector2d(1.5, 0.5)).norm(), 1e-12);
}

TEST(PlannedMotion, ATransitIsFollowedAtConstantSpeed) {
  HandPlan hand;
  const fesd::PlannedMotion motion(hand.task, {}, hand.legs, hand.transits);
  // Two pieces of equal length: the corner at half the transit's time.
  EXPECT_LT((motion.state(0.25).head<2>() - Eigen::Vector2d(-1.5, 0.5)).norm(), 1e-12);
  EXPECT_LT((motion.state(0.125).head<2>() - Eigen::Vector2d(-1.75, 0.25)).norm(), 1e-12);
  EXPECT_LT((motion.state(0.0).head<2>() - Eigen::Vector2d(-2, 0)).norm(), 1e-12);
}

TEST(PlannedMotion, AStoneInTheWayIsShovedAsTheProjectionWould) {
  HandPlan hand;
  hand.task.scene.bodies().push_back({"stone", 0.25, Eigen::Vector2d(2.0, 0.2), false});
  hand.task.bodies.emplace_back();
  const std::vector<fesd::ContactPair> pairs = hand.task.scene.allPairs();
  const fesd::PlannedMotion motion(hand.task, pairs, hand.legs, hand.transits);
  // The puck (R = 0.5) meets the stone (R = 0.25, 0.2 off the line) when its centre is at
  // 2 - sqrt(0.75^2 - 0.2^2) = 1.2772, at t = 0.5 + 1.2772 / 3: untouched before, shoved after.
  const double meeting = 0.5 + (2.0 - std::sqrt(0.75 * 0.75 - 0.04)) / 3.0;
  EXPECT_EQ(motion.state(meeting - 0.01).tail<2>(), Eigen::Vector2d(2.0, 0.2));
  EXPECT_GT((motion.state(meeting + 0.02).tail<2>() - Eigen::Vector2d(2.0, 0.2)).norm(), 0.0);
  const Eigen::VectorXd end = motion.state(1.5);
  EXPECT_GE((end.segment<2>(2) - end.tail<2>()).norm(), 0.75 - 1e-3);  // never overlapping
  EXPECT_GT(end(5), 0.2);  // shoved aside, the way the contact normal points
}

}  // namespace
