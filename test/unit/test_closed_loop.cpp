// Closed-loop execution (planning/closed_loop.cpp): replans after every few intervals from the
// state the plant reached, warm from the rest of the plan before, to the horizon.
#include <gtest/gtest.h>

#include "fesd_trajopt/planning/closed_loop.h"
#include "support/scene_tasks.h"

namespace {

TEST(ClosedLoop, ReplansFromThePlantsStateWarmUntilTheHorizon) {
  fesd::SceneTask task = fesd_test::pushAlongX();
  task.num_intervals = 10;
  fesd::ClosedLoopOptions options;
  options.replan_every = 4;
  options.first_accuracy = 0.0;
  options.first.ocp.discretization.num_elements = 2;
  options.replan = options.first;
  options.plant.discretization.num_elements = 4;
  const fesd::ClosedLoopRun run = fesd::executeWithFeedback(task, fesd::TaskLimits{}, options);
  ASSERT_EQ(run.status, fesd::SolveStatus::kSuccess) << run.message;
  ASSERT_EQ(run.replans.size(), 2u);  // after 4 and 8 of the 10 intervals
  EXPECT_EQ(run.replans[0].after_intervals, 4);
  EXPECT_EQ(run.replans[1].after_intervals, 8);
  for (const fesd::Replan& replan : run.replans) {
    EXPECT_EQ(replan.status, fesd::SolveStatus::kSuccess);
    EXPECT_TRUE(replan.warm_started);
  }
  // The plant's motion covers the horizon, in 4 + 4 + 2 intervals of 4 elements.
  EXPECT_EQ(run.executed.elements.size(), 40u);
  EXPECT_NEAR(run.executed.times.back(), task.horizon, 1e-12);
  EXPECT_EQ(run.end, run.executed.finalState());
  EXPECT_LT((task.scene.position(1, run.end) - task.bodies[1].target).norm(), 1e-2);
}

TEST(ClosedLoop, AnInvalidTaskEndsBeforeItStarts) {
  fesd::SceneTask task = fesd_test::pushAlongX();
  task.horizon = -1.0;
  const fesd::ClosedLoopRun run =
      fesd::executeWithFeedback(task, fesd::TaskLimits{}, fesd::ClosedLoopOptions{});
  EXPECT_NE(run.status, fesd::SolveStatus::kSuccess);
  EXPECT_NE(run.message.find("the first plan"), std::string::npos);
  EXPECT_TRUE(run.replans.empty());
}

}  // namespace
