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

TEST(ClosedLoop, AFirstPlanRefusedAsInfeasibleEndsItWithThatStatus) {
  fesd::SceneTask task = fesd_test::pushAlongX();
  task.bodies[1].target = Eigen::Vector2d(100.0, 0.0);  // beyond the pushers' reach in T = 2
  const fesd::ClosedLoopRun run =
      fesd::executeWithFeedback(task, fesd::TaskLimits{}, fesd::ClosedLoopOptions{});
  EXPECT_EQ(run.status, fesd::SolveStatus::kInfeasible);
  EXPECT_NE(run.message.find("the first plan: infeasible: body"), std::string::npos) << run.message;
  EXPECT_TRUE(run.replans.empty());
}

TEST(ClosedLoop, AReplanRefusedAsInfeasibleSaysSoAndThePlanBeforeRunsOn) {
  // A first plan that pushes nothing: after 18 of 20 intervals the pusher cannot bring the puck
  // 3 further in the 0.2 s left.
  const fesd::SceneTask task = fesd_test::pushAlongX();
  fesd::SceneOutcome idle;
  idle.status = fesd::SolveStatus::kSuccess;
  idle.trajectory.controls.assign(task.num_intervals,
                                  Eigen::VectorXd::Zero(task.scene.controlSize()));
  fesd::ClosedLoopOptions options;
  options.first_plan = &idle;
  options.replan_every = 18;
  const fesd::ClosedLoopRun run = fesd::executeWithFeedback(task, fesd::TaskLimits{}, options);
  ASSERT_EQ(run.status, fesd::SolveStatus::kSuccess) << run.message;
  ASSERT_EQ(run.replans.size(), 1u);
  EXPECT_EQ(run.replans[0].status, fesd::SolveStatus::kInfeasible);
  EXPECT_NE(run.replans[0].message.find("infeasible: body"), std::string::npos)
      << run.replans[0].message;
  EXPECT_NE(run.replans[0].message.find("cannot reach its target within the horizon"),
            std::string::npos);
  // The idle plan ran to the end: the puck where it started.
  EXPECT_LT(
      (task.scene.position(1, run.end) - task.scene.position(1, task.scene.initialState())).norm(),
      1e-9);
}

}  // namespace
