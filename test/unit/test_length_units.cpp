// One plan in any units (planning/length_units.cpp): trajectories and outcomes converted between
// length units (a wall's pair and a pair of spheres each in its own), a solve of a task in other
// units that is the task's own plan scaled (to the bit for a power of two), refusals in the
// user's units, and a warm start across a changed length scale refused.
#include "fesd_trajopt/planning/length_units.h"

#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/scene/scene_units.h"
#include "support/scene_tasks.h"

namespace {

using fesd::ContactPair;

/// One element of two stages with a pair of spheres (row 0) and a wall's pair (row 1).
fesd::Trajectory twoPairTrajectory() {
  fesd::Trajectory trajectory;
  trajectory.times = {0.0, 0.5};
  trajectory.states = {Eigen::Vector2d(1.0, 2.0), Eigen::Vector2d(3.0, -4.0)};
  trajectory.controls = {Eigen::Vector2d(0.5, -0.25)};
  fesd::ElementValues element;
  element.interval = 0;
  element.start_time = 0.0;
  element.step = 0.5;
  element.stage_states = Eigen::Matrix2d::Identity();
  element.stage_multipliers = (Eigen::Matrix2d() << 1.0, 2.0, 3.0, 4.0).finished();
  element.stage_constraints = (Eigen::Matrix2d() << 5.0, 6.0, 7.0, 8.0).finished();
  element.lowest_constraints = Eigen::Vector2d(-0.5, 0.25);
  trajectory.elements = {element};
  trajectory.interval_times = {0.0, 0.5};
  return trajectory;
}

TEST(LengthUnits, EachPairKeepsItsOwnUnits) {
  const std::vector<ContactPair> pairs{{0, ContactPair::Kind::kBody, 1},
                                       {0, ContactPair::Kind::kWall, 0}};
  fesd::Trajectory trajectory = twoPairTrajectory();
  fesd::scaleTrajectory(trajectory, pairs,
                        {10.0, Eigen::Vector2d::Constant(10.0), Eigen::Vector2d::Constant(10.0)});
  const fesd::ElementValues& element = trajectory.elements[0];
  EXPECT_EQ(trajectory.states[1], Eigen::Vector2d(30.0, -40.0));
  EXPECT_EQ(trajectory.controls[0], Eigen::Vector2d(5.0, -2.5));
  EXPECT_EQ(trajectory.times[1], 0.5);
  EXPECT_EQ(element.step, 0.5);
  EXPECT_EQ(element.stage_states, 10.0 * Eigen::Matrix2d::Identity());
  // |d|^2 - R^2 is an area, its force a rate; a wall's c a length, its force a speed.
  EXPECT_EQ(element.stage_constraints.row(0), Eigen::RowVector2d(500.0, 600.0));
  EXPECT_EQ(element.stage_constraints.row(1), Eigen::RowVector2d(70.0, 80.0));
  EXPECT_EQ(element.stage_multipliers.row(0), Eigen::RowVector2d(1.0, 2.0));
  EXPECT_EQ(element.stage_multipliers.row(1), Eigen::RowVector2d(30.0, 40.0));
  EXPECT_EQ(element.lowest_constraints, Eigen::Vector2d(-5.0, 2.5));
}

// A plan of a task in other units is the plan of the task, scaled: to the bit for a power of two
// (scaling is then exact), to rounding otherwise; the same Ipopt iterations either way.
TEST(LengthUnits, AScaledTaskGetsThePlanScaled) {
  const fesd::SceneTask task = fesd_test::pushAlongX();
  const fesd::SceneSolveOptions options = fesd_test::nodeGridOptions();
  const fesd::SceneOutcome plan = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  ASSERT_EQ(plan.status, fesd::SolveStatus::kSuccess) << plan.message;
  EXPECT_EQ(plan.length_scale, 0.5);
  for (const double k : {0.25, 0.01}) {
    SCOPED_TRACE(k);
    const fesd::SceneOutcome scaled =
        fesd::solveSceneTask(fesd::scaledTask(task, k), fesd::TaskLimits{}, options);
    ASSERT_EQ(scaled.status, fesd::SolveStatus::kSuccess) << scaled.message;
    EXPECT_EQ(scaled.report.iterations, plan.report.iterations);
    EXPECT_EQ(scaled.length_scale, k * 0.5);
    ASSERT_EQ(scaled.trajectory.states.size(), plan.trajectory.states.size());
    double deviation = 0.0;
    for (size_t i = 0; i < plan.trajectory.states.size(); ++i) {
      deviation = std::max(
          deviation,
          (scaled.trajectory.states[i] / k - plan.trajectory.states[i]).cwiseAbs().maxCoeff());
      EXPECT_EQ(scaled.trajectory.times[i], plan.trajectory.times[i]);
    }
    EXPECT_LE(deviation, k == 0.25 ? 0.0 : 1e-10);
    EXPECT_NEAR(scaled.report.objective / (k * k), plan.report.objective,
                1e-12 * plan.report.objective);
    EXPECT_NEAR(scaled.target_distances[1] / k, plan.target_distances[1], 1e-9);
  }
}

// The node's default request of the default scene at desk size and beyond: one plan, scaled.
TEST(LengthUnits, TheShowcaseInAnyUnitsIsOnePlan) {
  const fesd::SceneTask showcase = fesd::manipulation_example::task(40);
  const fesd::SceneSolveOptions options = fesd_test::nodeGridOptions();
  const fesd::SceneOutcome reference =
      fesd::solveToAccuracy(showcase, fesd::TaskLimits{}, options, 1e-2);
  ASSERT_EQ(reference.status, fesd::SolveStatus::kSuccess) << reference.message;
  ASSERT_FALSE(reference.trajectory.switches.empty());
  for (const double k : {0.25, 4.0, 0.01, 100.0}) {
    SCOPED_TRACE(k);
    const fesd::SceneOutcome outcome =
        fesd::solveToAccuracy(fesd::scaledTask(showcase, k), fesd::TaskLimits{}, options, 1e-2);
    ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
    EXPECT_EQ(outcome.report.iterations, reference.report.iterations);
    ASSERT_EQ(outcome.trajectory.switches.size(), reference.trajectory.switches.size());
    for (size_t s = 0; s < outcome.trajectory.switches.size(); ++s) {
      EXPECT_NEAR(outcome.trajectory.switches[s].time, reference.trajectory.switches[s].time, 1e-9);
    }
    EXPECT_NEAR(outcome.report.objective / (k * k), reference.report.objective,
                1e-9 * reference.report.objective);
    EXPECT_NEAR(outcome.verification.error / k, reference.verification.error,
                1e-6 * reference.verification.error);
    const bool power_of_two = k == 0.25 || k == 4.0;
    for (size_t i = 0; i < outcome.trajectory.states.size(); ++i) {
      const Eigen::VectorXd difference =
          outcome.trajectory.states[i] / k - reference.trajectory.states[i];
      EXPECT_LE(difference.cwiseAbs().maxCoeff(), power_of_two ? 0.0 : 1e-9);
    }
  }
}

// A yaw within its tolerance (1e-3 * 100 / weight rad) of its target is met, at any scale: the
// solve judges it with the user's weight, not its own (weight over L^2).
TEST(LengthUnits, AYawTargetWithinItsToleranceIsMetAtAnyScale) {
  fesd::SceneTask task = fesd_test::boxIntoACorner();
  task.bodies[0].max_speed = 0.0;  // nothing pushes the box
  task.bodies[1].target = task.scene.bodies()[1].position;
  task.bodies[1].target_yaw = task.scene.bodies()[1].yaw + 0.05;
  task.bodies[1].target_yaw_weight = 1.0;  // tolerance 0.1 rad
  for (const double k : {1.0, 0.1}) {
    SCOPED_TRACE(k);
    const fesd::SceneOutcome outcome = fesd::solveSceneTask(
        fesd::scaledTask(task, k), fesd::TaskLimits{}, fesd_test::nodeGridOptions());
    EXPECT_EQ(outcome.infeasible, "");
    EXPECT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  }
}

TEST(LengthUnits, RefusalsAndMessagesAreInTheUsersUnits) {
  fesd::SceneTask task = fesd::scaledTask(fesd_test::pushAlongX(), 0.01);
  task.bodies[1].workspace_upper = Eigen::Vector2d(0.02, 1.0);  // the target 0.03 is beyond it
  const fesd::SceneOutcome refused =
      fesd::solveSceneTask(task, fesd::TaskLimits{}, fesd_test::nodeGridOptions());
  EXPECT_FALSE(refused.solved());
  EXPECT_NE(refused.infeasible.find("outside its workspace"), std::string::npos)
      << refused.infeasible;
  // Beyond reach: the distance it stays away, in metres.
  fesd::SceneTask slow = fesd::scaledTask(fesd_test::pushAlongX(), 0.01);
  slow.bodies[0].max_speed = 0.0;
  const fesd::SceneOutcome stuck =
      fesd::solveSceneTask(slow, fesd::TaskLimits{}, fesd_test::nodeGridOptions());
  EXPECT_NE(stuck.infeasible.find("stays at least 0.03 away"), std::string::npos)
      << stuck.infeasible;
  // A radius refused, as given.
  fesd::SceneTask broken = fesd::scaledTask(fesd_test::pushAlongX(), 0.01);
  broken.scene.bodies()[1].radius = -0.002;
  const fesd::SceneOutcome invalid =
      fesd::solveSceneTask(broken, fesd::TaskLimits{}, fesd_test::nodeGridOptions());
  EXPECT_NE(invalid.invalid.find("has radius -0.002"), std::string::npos) << invalid.invalid;
  // The rock 100 away at scale 1 is 1.3 away at 0.01: the pruned pair says so in metres.
  const fesd::SceneTask rock = fesd::scaledTask(fesd_test::pushingTask(), 0.01);
  const fesd::SceneOutcome pruned =
      fesd::solveSceneTask(rock, fesd::TaskLimits{}, fesd_test::nodeGridOptions());
  std::string reason;
  for (const fesd::PairDecision& decision : pruned.decisions) {
    if (rock.scene.pairName(decision.pair) == "pusher/rock") reason = decision.reason;
  }
  EXPECT_NE(reason.find("stay 1.3"), std::string::npos) << reason;
  // A target the solve cannot reach in time, told in metres: the puck ends centimetres short.
  fesd::SceneTask far = fesd::scaledTask(fesd_test::pushAlongX(), 0.01);
  far.bodies[1].target = Eigen::Vector2d(0.1, 0.0);
  const fesd::SceneOutcome short_push =
      fesd::solveSceneTask(far, fesd::TaskLimits{}, fesd_test::nodeGridOptions());
  ASSERT_EQ(short_push.status, fesd::SolveStatus::kTargetNotReached) << short_push.message;
  const double left = short_push.target_distances[1];
  EXPECT_GT(left, 0.01);
  EXPECT_LT(left, 0.1);
  // Its tolerance 1e-3 of the length scale (the pusher's radius, 5 mm).
  EXPECT_NE(short_push.message.find("tolerance 5e-06"), std::string::npos) << short_push.message;
}

// The previous solve's NLP point is in its own units: a replan at another length scale starts
// from its plan (converted), not from that point; the same bodies keep the scale and the point.
TEST(LengthUnits, AWarmStartAcrossAnotherLengthScaleStartsFromThePlan) {
  const fesd::SceneTask task = fesd_test::pushAlongX();
  const fesd::SceneOutcome plan =
      fesd::solveSceneTask(task, fesd::TaskLimits{}, fesd_test::nodeGridOptions());
  ASSERT_EQ(plan.status, fesd::SolveStatus::kSuccess) << plan.message;
  fesd::SceneTask bigger = task;
  bigger.scene.bodies()[0].radius = 0.6;  // the pusher sets the length scale
  fesd::SceneSolveOptions options = fesd_test::nodeGridOptions();
  options.previous = &plan;
  const fesd::SceneOutcome replan = fesd::solveSceneTask(bigger, fesd::TaskLimits{}, options);
  EXPECT_EQ(replan.status, fesd::SolveStatus::kSuccess) << replan.message;
  EXPECT_TRUE(replan.warm_started);
  EXPECT_EQ(replan.start, fesd::OcpStart::kTrajectory);
  EXPECT_EQ(replan.plan_source, "previous plan after 0 interval(s)");
  fesd::SceneTask moved = task;
  moved.bodies[1].target = Eigen::Vector2d(3.1, 0.1);
  const fesd::SceneOutcome warm = fesd::solveSceneTask(moved, fesd::TaskLimits{}, options);
  EXPECT_TRUE(warm.warm_started) << warm.cold_start_reason;
  EXPECT_EQ(warm.start, fesd::OcpStart::kPrevious);
}

}  // namespace
