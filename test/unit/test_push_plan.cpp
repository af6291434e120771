// The push plan (planPushes), the first guess of scene OCPs: pushing poses, phase times, a
// guess whose states, forces and controls are consistent with the scene's dynamics (its
// residual in the OCP's equations), legs round a post with the pusher turning behind the puck,
// a pusher that must go round the puck first, a push along a wall, and what it does with bodies
// in the way (shoves them as a chain).
#include <algorithm>
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/planning/push_plan.h"
#include "fesd_trajopt/scene/pair_check.h"
#include "support/scene_tasks.h"

namespace {

namespace example = fesd::manipulation_example;

TEST(PushPlan, TheShowcasePushersSitBehindTheObjectWithinTheirWorkspaces) {
  const fesd::PushPlan plan = example::plan(40);
  ASSERT_EQ(plan.pushes.size(), 2u);
  // Straight behind the upward push (0, -3) is outside both workspaces (x <= -2.5, x >= 2.5):
  // the closest poses on the contact circle of radius 3 keep x at the bound.
  for (const fesd::PushAssignment& push : plan.pushes) {
    EXPECT_EQ(push.pushed, 2);
    EXPECT_NEAR(push.offset.norm(), 3.0, 1e-12);
    EXPECT_LT(push.offset.y(), 0.0);
  }
  EXPECT_LE(plan.pushes[0].offset.x(), -2.5);
  EXPECT_GE(plan.pushes[1].offset.x(), 2.5);
  EXPECT_NEAR(plan.pushes[0].offset.x(), -2.5, 0.06);  // within one 1-degree candidate step
  EXPECT_NEAR(plan.pushes[1].offset.x(), 2.5, 0.06);
  EXPECT_GT(plan.contact_time, 0.0);
  EXPECT_LT(plan.contact_time, plan.release_time);
  EXPECT_LT(plan.release_time, 5.0);
}

TEST(PushPlan, PhaseTimesHaveTheLeastControlEffort) {
  // Phase i costs c_i / tau_i with c_i its summed squared control displacements; the least sum
  // under tau_0 + tau_1 + tau_2 = T has tau_i ~ sqrt(c_i), i.e. the same |u|^2 (summed over
  // the pushers) in every phase. Check it on the intervals that lie inside one phase.
  const fesd::PushPlan plan = example::plan(40);
  const double horizon = example::task(40).horizon;
  const int intervals = static_cast<int>(plan.guess.controls.size());
  std::vector<double> squared_speeds[3];
  for (int k = 0; k < intervals; ++k) {
    const double begin = k * horizon / intervals, end = (k + 1) * horizon / intervals;
    const int phase = end <= plan.contact_time                                 ? 0
                      : begin >= plan.release_time                             ? 2
                      : begin >= plan.contact_time && end <= plan.release_time ? 1
                                                                               : -1;
    if (phase >= 0) squared_speeds[phase].push_back(plan.guess.controls[k].squaredNorm());
  }
  const double reference = squared_speeds[1].front();
  for (const auto& phase : squared_speeds) {
    ASSERT_FALSE(phase.empty());
    for (double value : phase) EXPECT_NEAR(value / reference, 1.0, 1e-6);
  }
}

TEST(PushPlan, TheGuessMovesTheObjectByTheForcesItCarries) {
  const fesd::PushPlan plan = example::plan(40);
  const fesd::SceneTask task = example::task(40);
  const auto model = task.scene.model(example::contactPairs());
  const double t1 = plan.contact_time, t2 = plan.release_time;
  // Start, end of the approach (pushers in contact), end of the push (object at its goal).
  EXPECT_LT((plan.guess.state(0.0) - task.scene.initialState()).norm(), 1e-12);
  const Eigen::VectorXd at_release = plan.guess.state(t2);
  EXPECT_LT((at_release.tail<2>() - example::objectGoal()).norm(), 1e-12);
  Eigen::VectorXd c(2);
  model->constraints()->evaluate(at_release.data(), c.data());
  EXPECT_NEAR(c(0), 0.0, 1e-9);
  EXPECT_NEAR(c(1), 0.0, 1e-9);
  // During the push: xdot = f(x, u) + grad c(x) lambda holds for the object (passive) exactly.
  const double t = 0.5 * (t1 + t2), dt = 1e-6;
  const Eigen::VectorXd x = plan.guess.state(t);
  const Eigen::VectorXd velocity = (plan.guess.state(t + dt) - plan.guess.state(t - dt)) / (2 * dt);
  const Eigen::VectorXd lambda = plan.guess.multipliers(t);
  ASSERT_EQ(lambda.size(), 2);
  EXPECT_GT(lambda.minCoeff(), 0.0);
  Eigen::VectorXd z(6 + 4 + 2), v(6);
  z << x, Eigen::VectorXd::Zero(4), lambda;
  model->velocity()->evaluate(z.data(), v.data());
  EXPECT_LT((v.tail<2>() - velocity.tail<2>()).norm(), 1e-6);
  // No force before the contact or after the release.
  EXPECT_EQ(plan.guess.multipliers(0.5 * t1).norm(), 0.0);
  EXPECT_EQ(plan.guess.multipliers(0.5 * (t2 + 5.0)).norm(), 0.0);
}

TEST(PushPlan, NothingToPushMovesActuatorsStraightToTheirTargets) {
  fesd::SceneTask task = example::task(10);
  task.bodies[2].target_weight = 0.0;  // the object has no goal
  const fesd::PushPlan plan = fesd::planPushes(task, example::contactPairs());
  EXPECT_TRUE(plan.pushes.empty());
  EXPECT_DOUBLE_EQ(plan.contact_time, task.horizon);
  const Eigen::VectorXd end = plan.guess.state(task.horizon);
  EXPECT_LT((end.head<2>() - task.bodies[0].target).norm(), 1e-12);
  EXPECT_LT((end.segment<2>(2) - task.bodies[1].target).norm(), 1e-12);
  EXPECT_LT((end.tail<2>() - task.scene.bodies()[2].position).norm(), 1e-12);
}

TEST(PushPlan, PathsStepAroundWhatTheyWouldPassThrough) {
  // One actuator whose straight path to its target crosses an obstacle's centre.
  fesd::SceneTask task;
  task.scene = fesd::Scene(2);
  task.scene.bodies() = {{"pusher", 0.5, Eigen::Vector2d(-3.0, 0.0), true}};
  task.scene.obstacles() = {{"post", 1.0, Eigen::Vector2d(0.0, 0.0)}};
  fesd::BodyTask pusher;
  pusher.target = Eigen::Vector2d(3.0, 0.0);
  pusher.target_weight = 1.0;
  task.bodies = {pusher};
  task.horizon = 2.0;
  task.num_intervals = 8;
  const fesd::PushPlan plan = fesd::planPushes(task, {});
  for (double t = 0.0; t <= 2.0; t += 0.05) {
    EXPECT_GE(plan.guess.state(t).norm(), 1.5 - 1e-12) << "t = " << t;
  }
}

TEST(PushPlan, ABodyInThePushedBodysWayIsShovedAlongAsTheProjectionWould) {
  fesd::SceneTask task = fesd_test::pushAlongX();
  task.scene.bodies().push_back({"rock", 0.5, Eigen::Vector2d(1.5, 0.3), false});
  task.bodies.emplace_back();
  const std::vector<fesd::ContactPair> pairs = task.scene.allPairs();  // pusher/puck first
  const fesd::ContactPair puck_rock{1, fesd::ContactPair::Kind::kBody, 2};
  const int chain =
      static_cast<int>(std::find(pairs.begin(), pairs.end(), puck_rock) - pairs.begin());
  const fesd::PushPlan plan = fesd::planPushes(task, pairs);
  // The puck reaches its target straight; the rock is pushed off the puck's path, never
  // overlapping it (the simulation's steps move nothing by more than 5 % of a radius).
  EXPECT_LT((plan.guess.state(plan.release_time).segment<2>(2) - Eigen::Vector2d(3, 0)).norm(),
            1e-12);
  double pressed = 0.0;
  for (double t = 0.0; t <= task.horizon; t += 0.01) {
    const Eigen::VectorXd x = plan.guess.state(t);
    EXPECT_GT(task.scene.pairGap(puck_rock, x), -1e-3) << "t = " << t;
    pressed = std::max(pressed, plan.guess.multipliers(t)(chain));
  }
  EXPECT_GT(pressed, 0.0);
  const Eigen::VectorXd end = plan.guess.state(task.horizon);
  EXPECT_GT(end(4), 1.6);  // shoved forward ...
  EXPECT_GT(end(5), 0.5);  // ... and aside, the way the contact normal points
  // While shoved, the rock moves as the contact force moves it: v_rock = lambda grad c.
  double t_shove = -1.0;
  for (double t = plan.contact_time; t < plan.release_time; t += 0.01) {
    if (plan.guess.multipliers(t)(chain) > 0.0) {
      t_shove = t + 0.02;
      break;
    }
  }
  ASSERT_GT(t_shove, 0.0);
  const double dt = 1e-4;
  const Eigen::VectorXd x = plan.guess.state(t_shove);
  const Eigen::Vector2d velocity =
      (plan.guess.state(t_shove + dt) - plan.guess.state(t_shove - dt)).tail<2>() / (2 * dt);
  const Eigen::Vector2d force =
      plan.guess.multipliers(t_shove)(chain) * 2.0 * (x.tail<2>() - x.segment<2>(2));
  EXPECT_LT((velocity - force).norm(), 0.05 * velocity.norm());
}

/// The largest residual of the OCP's equations (dynamics, algebraic) at the plan's guess.
double guessResidual(const fesd::SceneTask& task, const std::vector<fesd::ContactPair>& pairs,
                     const fesd::PushPlan& plan) {
  fesd::OcpOptions options;
  options.discretization.num_elements = 3;
  const fesd::OcpSolver solver(fesd::buildOcp(task, pairs), options);
  return solver.discretization().nlp().equalityResidual(
      solver.discretization().guessFrom(plan.guess).data());
}

TEST(PushPlan, AStraightPushIsOneLegWithAGuessThatSatisfiesTheDynamics) {
  const fesd::SceneTask task = fesd_test::pushAlongX();
  const std::vector<fesd::ContactPair> pairs = task.scene.allPairs();
  const fesd::PushPlan plan = fesd::planPushes(task, pairs);
  ASSERT_EQ(plan.legs.size(), 1u);
  EXPECT_TRUE(plan.legs[0].through.empty());
  EXPECT_EQ(plan.legs[0].begin, plan.contact_time);
  EXPECT_EQ(plan.legs[0].end, plan.release_time);
  ASSERT_EQ(plan.legs[0].pushes.size(), 1u);
  EXPECT_LT((plan.legs[0].pushes[0].offset - Eigen::Vector2d(-1.0, 0.0)).norm(), 1e-12);
  ASSERT_EQ(plan.transits.size(), 1u);  // the approach; the pusher has no target to return to
  EXPECT_EQ(plan.transits[0].path.size(), 2u);
  // What is left is the mean controls against a motion whose contact starts mid-interval.
  EXPECT_LT(guessResidual(task, pairs, plan), 0.02);
}

TEST(PushPlan, APostInTheWayIsGoneRoundInLegsWithThePusherTurningBehindThePuck) {
  fesd::SceneTask task = fesd_test::pushAlongX();
  task.scene.obstacles() = {{"post", 0.4, Eigen::Vector2d(1.5, 0.0)}};  // dead ahead
  const std::vector<fesd::ContactPair> pairs = task.scene.allPairs();
  const fesd::PushPlan plan = fesd::planPushes(task, pairs);
  ASSERT_EQ(plan.legs.size(), 1u);
  const fesd::PushLeg& push = plan.legs[0];
  ASSERT_FALSE(push.through.empty());
  EXPECT_LE(push.through.size(), 2u);
  EXPECT_DOUBLE_EQ(push.turn_radius, 1.0);  // the puck's and the pusher's radii
  // The legs keep the post's and the puck's radii (0.9) from the post, the pusher straight
  // behind the first leg.
  const Eigen::Vector2d post(1.5, 0.0);
  std::vector<Eigen::VectorXd> corners{push.from};
  corners.insert(corners.end(), push.through.begin(), push.through.end());
  corners.push_back(push.to);
  for (size_t j = 1; j < corners.size(); ++j) {
    EXPECT_GE(fesd::segmentDistance(post, corners[j - 1], corners[j]), 0.9 - 1e-9) << "leg " << j;
  }
  const Eigen::VectorXd first = (corners[1] - corners[0]).normalized();
  EXPECT_LT((push.pushes[0].offset + first).norm(), 1e-12);
  const fesd::ContactPair puck_post{1, fesd::ContactPair::Kind::kObstacle, 0};
  const fesd::ContactPair pusher_post{0, fesd::ContactPair::Kind::kObstacle, 0};
  const fesd::ContactPair pusher_puck{0, fesd::ContactPair::Kind::kBody, 1};
  for (double t = 0.0; t <= task.horizon; t += 0.002) {
    const Eigen::VectorXd x = plan.guess.state(t);
    EXPECT_GT(task.scene.pairGap(puck_post, x), 0.0) << "t = " << t;
    EXPECT_GT(task.scene.pairGap(pusher_post, x), 0.0) << "t = " << t;
    EXPECT_GT(task.scene.pairGap(pusher_puck, x), -1e-9) << "t = " << t;
    if (t > plan.contact_time && t < plan.release_time) {  // in contact all along the push
      EXPECT_LT(task.scene.pairGap(pusher_puck, x), 1e-9) << "t = " << t;
    }
  }
  EXPECT_LT((plan.guess.state(plan.release_time).segment<2>(2) - Eigen::Vector2d(3, 0)).norm(),
            1e-12);
  EXPECT_LT(guessResidual(task, pairs, plan), 0.25);
}

TEST(PushPlan, APusherInFrontOfThePuckGoesRoundItToPushFromBehind) {
  fesd::SceneTask task = fesd_test::pushAlongX();
  task.scene.bodies()[0].position = Eigen::Vector2d(2.0, 0.2);  // ahead, nearly on the line
  const std::vector<fesd::ContactPair> pairs = task.scene.allPairs();
  const fesd::PushPlan plan = fesd::planPushes(task, pairs);
  ASSERT_EQ(plan.legs.size(), 1u);
  ASSERT_FALSE(plan.transits.empty());
  const fesd::Transit& approach = plan.transits.front();
  EXPECT_EQ(approach.body, 0);
  EXPECT_GT(approach.path.size(), 2u);
  EXPECT_LT((approach.path.back() - Eigen::Vector2d(-1.0, 0.0)).norm(), 1e-12);
  const fesd::ContactPair pusher_puck{0, fesd::ContactPair::Kind::kBody, 1};
  for (double t = 0.0; t <= plan.contact_time; t += 0.002) {
    EXPECT_GT(task.scene.pairGap(pusher_puck, plan.guess.state(t)), -1e-9) << "t = " << t;
  }
  // The puck rests until the pusher is behind it.
  EXPECT_EQ(plan.guess.state(0.99 * plan.contact_time).segment<2>(2),
            task.scene.bodies()[1].position);
}

TEST(PushPlan, APushAlongAWallIsOneStraightLeg) {
  fesd::SceneTask task = fesd_test::pushAlongX();
  task.scene.walls() = {{"wall", Eigen::Vector2d(0.0, 1.0), -0.5}};  // touching the puck
  const std::vector<fesd::ContactPair> pairs = task.scene.allPairs();
  const fesd::PushPlan plan = fesd::planPushes(task, pairs);
  ASSERT_EQ(plan.legs.size(), 1u);
  EXPECT_TRUE(plan.legs[0].through.empty());  // straight along the wall, no turns
  for (double t = 0.0; t <= task.horizon; t += 0.01) {
    const Eigen::VectorXd x = plan.guess.state(t);
    EXPECT_GE(x(1), -1e-12) << "pusher, t = " << t;
    EXPECT_GE(x(3), -1e-12) << "puck, t = " << t;
  }
}

TEST(PushPlan, ATargetBeyondThePushersReachIsReplacedByTheNearestEndTheyCanPushTo) {
  // The showcase's actuators stay at |x| >= 2.5, 3 from the object's centre in contact: behind
  // an object at x > 0.5 only actuator_2 fits, and it cannot push it straight up.
  const fesd::SceneTask reachable = example::task(40, Eigen::Vector2d(0.3, 10.0));
  EXPECT_TRUE(fesd::planPushes(reachable, example::contactPairs()).short_pushes.empty());
  const Eigen::Vector2d target(1.2, 10.0);
  const fesd::PushPlan plan = fesd::planPushes(example::task(40, target), example::contactPairs());
  ASSERT_EQ(plan.short_pushes.size(), 1u);
  EXPECT_EQ(plan.short_pushes[0].body, 2);
  const Eigen::VectorXd end = plan.short_pushes[0].end;
  EXPECT_GT(end.x(), 0.2);  // as far right as both actuators can still push from behind
  EXPECT_LT(end.x(), 0.6);
  EXPECT_LT((end - target).norm(), 1.0);
  ASSERT_EQ(plan.pushes.size(), 2u);  // both push, to the end the plan aims at
  EXPECT_LT((plan.guess.state(plan.release_time).segment<2>(4) - end).norm(), 1e-6);
}

TEST(PushPlan, ATargetOutOfTimeIsPushedAsFarAsTimeAllowsWithinTheSpeedBounds) {
  // The pusher (|u_d| <= 2) 2 from its pose behind the puck: 1 s to get there, then 1 s pushing
  // at half its speed (one pusher shares the push with the puck): the puck gets to x = 1.
  fesd::SceneTask task = fesd_test::pushingTask();
  task.bodies[1].target_weight = 100.0;
  task.bodies[1].target = Eigen::Vector2d(0.8, 0.0);
  EXPECT_TRUE(fesd::planPushes(task, task.scene.allPairs()).short_pushes.empty());
  task.bodies[1].target = Eigen::Vector2d(1.5, 0.0);
  const fesd::PushPlan plan = fesd::planPushes(task, task.scene.allPairs());
  ASSERT_EQ(plan.short_pushes.size(), 1u);
  EXPECT_TRUE(plan.short_pushes[0].time_limited);
  EXPECT_LT((plan.short_pushes[0].end - Eigen::Vector2d(1.0, 0.0)).norm(), 1e-5);
  EXPECT_NEAR(plan.contact_time, 1.0, 1e-5);  // the approach at full speed
  EXPECT_NEAR(plan.release_time, 2.0, 1e-5);
  for (const Eigen::VectorXd& u : plan.guess.controls)
    EXPECT_LE(u.cwiseAbs().maxCoeff(), 2.0 + 1e-4);
  // A second pusher that cannot move (speed bound 0) leaves the push to the first: placed beside
  // it, tilted, its force is not needed and it is not kept.
  fesd::SceneTask helped = task;
  helped.bodies[1].target = Eigen::Vector2d(0.8, 0.0);
  helped.scene.bodies().push_back({"idle", 0.5, Eigen::Vector2d(-3.0, 3.0), true});
  helped.bodies.push_back(fesd::BodyTask{});
  helped.bodies.back().max_speed = 0.0;
  const fesd::PushPlan both = fesd::planPushes(helped, helped.scene.allPairs());
  ASSERT_EQ(both.pushes.size(), 1u);
  EXPECT_EQ(both.pushes[0].pusher, 0);
  EXPECT_LT(both.contact_time, both.release_time);
  EXPECT_LT((both.guess.state(helped.horizon).segment<2>(2) - Eigen::Vector2d(0.8, 0.0)).norm(),
            1e-6);
  // A pusher too slow to arrive at all: no push is planned, and it never sits on the puck.
  fesd::SceneTask slow = task;
  slow.bodies[0].max_speed = 0.5;
  const fesd::PushPlan none = fesd::planPushes(slow, slow.scene.allPairs());
  ASSERT_EQ(none.short_pushes.size(), 1u);
  EXPECT_EQ(none.short_pushes[0].end, slow.scene.bodies()[1].position);
  EXPECT_TRUE(none.pushes.empty());
  for (int k = 0; k <= 20; ++k) {
    const Eigen::VectorXd x = none.guess.state(slow.horizon * k / 20);
    EXPECT_GE((x.segment<2>(0) - x.segment<2>(2)).norm(), 1.0 - 1e-9) << "t = " << k;
  }
  // Out of the workspace, not of time: not time-limited.
  task.bodies[1].workspace_upper = Eigen::Vector2d(0.5, 10.0);
  task.bodies[1].workspace_lower = Eigen::Vector2d(-10.0, -10.0);
  task.bodies[0].workspace_upper = Eigen::Vector2d(-0.5, 10.0);
  task.bodies[0].workspace_lower = Eigen::Vector2d(-10.0, -10.0);
  const fesd::PushPlan bounded = fesd::planPushes(task, task.scene.allPairs());
  ASSERT_EQ(bounded.short_pushes.size(), 1u);
  EXPECT_FALSE(bounded.short_pushes[0].time_limited);
}

TEST(PushPlan, ATargetInsideAnObstacleIsReplacedByAnEndClearOfIt) {
  fesd::SceneTask task = example::task(40, Eigen::Vector2d(0.0, 10.0));
  task.scene.obstacles().push_back({"rock", 1.0, Eigen::Vector2d(0.0, 10.5)});
  const fesd::PushPlan plan = fesd::planPushes(task, example::contactPairs());
  ASSERT_EQ(plan.short_pushes.size(), 1u);
  const double clearance = (plan.short_pushes[0].end - Eigen::Vector2d(0.0, 10.5)).norm();
  EXPECT_GE(clearance, 3.0);  // the object's radius 2 plus the rock's 1
  EXPECT_LT(clearance, 3.0 + 0.1);
}

}  // namespace
