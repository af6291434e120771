// Plans verified interval by interval and executed open and closed loop (planning/
// plan_verification.cpp, closed_loop.cpp): a disc pushed by one disc is open-loop unstable, one
// held between two pushers (the showcase) far less; the interval error stays small either way,
// and with feedback the push ends where it was meant to.
#include <cstdio>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/planning/closed_loop.h"
#include "support/scene_tasks.h"

namespace {

/// A pusher (R = 0.5, |u| <= 4) from (-2, 0) pushes a puck from the origin to (5, 3) in 5 s on 40
/// intervals.
fesd::SceneTask longPush() {
  fesd::SceneTask task = fesd_test::pushAlongX();
  task.bodies[1].target = Eigen::Vector2d(5.0, 3.0);
  task.horizon = 5.0;
  task.num_intervals = 40;
  return task;
}

TEST(OpenLoop, OnePusherIsUnstableTwoHoldTheBodyAndBothPlansVerify) {
  const fesd::SceneOutcome one =
      fesd::solveToAccuracy(longPush(), fesd::TaskLimits{}, fesd_test::nodeGridOptions(), 1e-2);
  const fesd::SceneOutcome two = fesd::solveToAccuracy(
      fesd::manipulation_example::task(40), fesd::TaskLimits{}, fesd_test::nodeGridOptions(), 1e-2);
  for (const fesd::SceneOutcome* outcome : {&one, &two}) {
    ASSERT_EQ(outcome->status, fesd::SolveStatus::kSuccess) << outcome->message;
    ASSERT_TRUE(outcome->verified);
    EXPECT_EQ(outcome->refinements.size(), 1u);
    EXPECT_LT(outcome->verification.error, 1e-4);
    EXPECT_TRUE(outcome->verification.grazes.empty());
    std::printf("interval error %.3g, open loop %.3g, gain %.3g (%s)\n",
                outcome->verification.error, outcome->verification.open_loop_error,
                outcome->verification.open_loop_gain, outcome->verification.gain_note.c_str());
  }
  EXPECT_GT(one.verification.open_loop_gain, 1e3);
  EXPECT_LT(two.verification.open_loop_gain, 1e3);
  EXPECT_GT(one.verification.open_loop_gain, 10.0 * two.verification.open_loop_gain);
  // Open loop the push drifts far beyond its interval errors.
  EXPECT_GT(one.verification.open_loop_error, 100.0 * one.verification.error);
}

TEST(ClosedLoop, AnUnstablePushEndsAtItsTargetWithFeedback) {
  const fesd::SceneTask task = longPush();
  fesd::ClosedLoopOptions options;
  options.first = fesd_test::nodeGridOptions();
  options.replan = fesd_test::nodeGridOptions();
  options.replan.verify = false;
  options.plant.discretization.num_stages = 3;
  options.plant.discretization.num_elements = 6;
  const fesd::ClosedLoopRun run = fesd::executeWithFeedback(task, fesd::TaskLimits{}, options);
  ASSERT_EQ(run.status, fesd::SolveStatus::kSuccess) << run.message;
  const Eigen::VectorXd target = task.bodies[1].target;
  const fesd::Verification& open = run.first.verification;
  const double open_miss = (task.scene.position(1, open.open_loop.finalState()) - target).norm();
  const double closed_miss = (task.scene.position(1, run.end) - target).norm();
  ASSERT_EQ(run.replans.size(), 13u);  // after 3, 6, .., 39 of the 40 intervals
  int iterations = 0;
  for (const fesd::Replan& replan : run.replans) {
    EXPECT_EQ(replan.status, fesd::SolveStatus::kSuccess) << replan.after_intervals;
    EXPECT_TRUE(replan.warm_started) << replan.after_intervals;
    // The plant drifted a little from the plan: the rest of it polished in a few iterations.
    EXPECT_LE(replan.iterations, 20) << replan.after_intervals;
    iterations += replan.iterations;
  }
  std::printf(
      "closed loop: open loop misses by %.3g, closed loop by %.3g; first plan %d "
      "iterations (%.3f s), 13 replans %d (%.3f s)\n",
      open_miss, closed_miss, run.first.report.iterations, run.first_seconds, iterations,
      run.replan_seconds);
  EXPECT_GT(open_miss, 0.1);
  EXPECT_LT(closed_miss, 1e-2);
}

}  // namespace
