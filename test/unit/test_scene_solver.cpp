// The scene entry points: one call from a task to a full-scene trajectory, for planning and for
// simulation, refusing what must not be solved.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/scene/scene_solver.h"
#include "support/scene_tasks.h"

namespace {

using fesd_test::pushingTask;

fesd::SimulationOptions twoElements() {
  fesd::SimulationOptions options;
  options.discretization.num_elements = 2;
  return options;
}

TEST(SimulateSceneTask, PushesThePuckAsTheProjectionPredictsWhateverTheOcpBounds) {
  fesd::SceneTask task = pushingTask();
  // OCP settings a simulation ignores: the reach comes from the commands, and workspace bounds
  // are no physics.
  task.bodies[0].max_speed = 0.1;
  task.bodies[1].workspace_lower = Eigen::Vector2d(-1.0, -1.0);
  task.bodies[1].workspace_upper = Eigen::Vector2d(0.5, 1.0);
  const fesd::SceneOutcome outcome =
      fesd::simulateSceneTask(task, {Eigen::Vector2d(2.0, 0.0)}, fesd::TaskLimits{}, twoElements());
  ASSERT_TRUE(outcome.solved()) << outcome.invalid;
  ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  EXPECT_EQ(outcome.moving_bodies, (std::vector<int>{0, 1}));
  EXPECT_EQ(outcome.modelledPairs(), 1);
  EXPECT_EQ(outcome.decisions.size(), 3u);
  // Contact at t = 1, then both move at 1 m/s: pusher (0, 0), puck (1, 0); the rock stays.
  Eigen::VectorXd expected(6);
  expected << 0.0, 0.0, 1.0, 0.0, 100.0, 100.0;
  EXPECT_LT((outcome.trajectory.finalState() - expected).norm(), 1e-9);
  ASSERT_FALSE(outcome.trajectory.switches.empty());
  EXPECT_NEAR(outcome.trajectory.switches.front().time, 1.0, 1e-9);
  EXPECT_GT(outcome.report.iterations, 0);
}

TEST(SimulateSceneTask, RefusesControlsOfTheWrongCountSizeOrValue) {
  const fesd::SceneTask task = pushingTask();
  const fesd::TaskLimits limits;
  const Eigen::Vector2d u(1.0, 0.0);
  EXPECT_NE(fesd::simulateSceneTask(task, {u, u}, limits, twoElements()).invalid.find("one per"),
            std::string::npos);
  EXPECT_NE(fesd::simulateSceneTask(task, {Eigen::Vector3d::Zero()}, limits, twoElements())
                .invalid.find("control size"),
            std::string::npos);
  EXPECT_NE(fesd::simulateSceneTask(task, {Eigen::Vector2d(NAN, 0.0)}, limits, twoElements())
                .invalid.find("finite"),
            std::string::npos);
  fesd::SceneTask overlapping = task;
  overlapping.scene.bodies()[1].position(0) = -2.5;
  const fesd::SceneOutcome refused =
      fesd::simulateSceneTask(overlapping, {u}, limits, twoElements());
  EXPECT_NE(refused.invalid.find("overlap"), std::string::npos) << refused.invalid;
  EXPECT_TRUE(refused.trajectory.states.empty());
}

TEST(SolveSceneTask, RefusesInvalidTasksAndNamesUnreachableTargetsWithoutSolving) {
  fesd::SceneTask invalid = pushingTask();
  invalid.scene.bodies()[1].radius = -1.0;
  const fesd::SceneOutcome refused =
      fesd::solveSceneTask(invalid, fesd::TaskLimits{}, fesd::SceneSolveOptions{});
  EXPECT_NE(refused.invalid.find("radius"), std::string::npos) << refused.invalid;
  EXPECT_FALSE(refused.solved());

  fesd::SceneTask unreachable = pushingTask();
  unreachable.bodies[2].target = Eigen::Vector2d(0.0, 0.0);  // the rock: nothing can push it
  unreachable.bodies[2].target_weight = 1.0;
  const fesd::SceneOutcome infeasible =
      fesd::solveSceneTask(unreachable, fesd::TaskLimits{}, fesd::SceneSolveOptions{});
  EXPECT_EQ(infeasible.invalid, "");
  EXPECT_NE(infeasible.infeasible.find("rock"), std::string::npos) << infeasible.infeasible;
  EXPECT_TRUE(infeasible.trajectory.states.empty());
  EXPECT_EQ(infeasible.report.iterations, 0);
}

TEST(SolveSceneTask, PushesThePuckToItsTargetOnlyModellingWhatCanTouch) {
  fesd::SceneTask task = pushingTask();
  task.bodies[1].target = Eigen::Vector2d(1.0, 0.0);
  task.bodies[1].target_weight = 100.0;
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 2;
  options.verify = true;
  options.verification.num_elements = 4;
  options.verification.num_stages = 3;
  const fesd::SceneOutcome pruned = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  ASSERT_TRUE(pruned.solved()) << pruned.invalid << pruned.infeasible;
  ASSERT_EQ(pruned.status, fesd::SolveStatus::kSuccess) << pruned.message;
  EXPECT_EQ(pruned.moving_bodies, (std::vector<int>{0, 1}));
  EXPECT_EQ(pruned.modelledPairs(), 1);
  const Eigen::VectorXd final_state = pruned.trajectory.finalState();
  ASSERT_EQ(final_state.size(), 6);
  EXPECT_LT((final_state.segment<2>(2) - Eigen::Vector2d(1.0, 0.0)).norm(), 0.05);
  EXPECT_EQ(final_state.tail<2>(), Eigen::Vector2d(100.0, 100.0));
  EXPECT_GT(pruned.sizes.complementarities, 0);
  EXPECT_TRUE(pruned.verified);
  EXPECT_LT(pruned.verification_error, 1e-6);

  // Every pair modelled: the rock moves with the rest (three bodies' states), same answer.
  options.prune_pairs = false;
  options.lazy_pairs = false;
  options.verify = false;
  const fesd::SceneOutcome full = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  ASSERT_EQ(full.status, fesd::SolveStatus::kSuccess) << full.message;
  EXPECT_EQ(full.modelledPairs(), 3);
  EXPECT_EQ(full.moving_bodies.size(), 3u);
  EXPECT_GT(full.sizes.variables, pruned.sizes.variables);
  EXPECT_FALSE(full.verified);
  EXPECT_LT((full.trajectory.finalState() - final_state).norm(), 1e-6);
}

TEST(SolveSceneTask, LazyPairsModelWhatThePushNeedsAndCheckTheRestOnTheAnswer) {
  // A rock in reach beside the push: the pusher and the puck could touch it, the plan never does.
  fesd::SceneTask task = pushingTask();
  task.scene.bodies()[2].position = Eigen::Vector2d(0.5, 2.0);
  task.bodies[1].target = Eigen::Vector2d(1.0, 0.0);
  task.bodies[1].target_weight = 100.0;
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 2;
  const fesd::SceneOutcome lazy = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  ASSERT_EQ(lazy.status, fesd::SolveStatus::kSuccess) << lazy.message;
  EXPECT_EQ(lazy.pair_rounds, 1);
  EXPECT_EQ(lazy.modelledPairs(), 1);
  EXPECT_EQ(lazy.checkedPairs(), 2);
  EXPECT_EQ(lazy.moving_bodies, (std::vector<int>{0, 1}));
  for (const fesd::PairDecision& d : lazy.decisions) {
    EXPECT_FALSE(std::isnan(d.min_distance)) << task.scene.pairName(d.pair);
    if (d.checked) {
      EXPECT_GT(d.min_distance, options.pair_margin * 1.0) << task.scene.pairName(d.pair);
      EXPECT_NE(d.reason.find("checked on the solution"), std::string::npos) << d.reason;
    } else {
      EXPECT_GT(d.min_distance, -1e-9);  // the modelled pair, at its stage points
    }
  }
  // Every pair in reach from the start: the same plan in a larger NLP.
  options.lazy_pairs = false;
  const fesd::SceneOutcome all = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  ASSERT_EQ(all.status, fesd::SolveStatus::kSuccess) << all.message;
  EXPECT_EQ(all.modelledPairs(), 3);
  EXPECT_EQ(all.checkedPairs(), 0);
  EXPECT_GT(all.sizes.variables, lazy.sizes.variables);
  EXPECT_NEAR(all.report.objective, lazy.report.objective, 1e-6 * lazy.report.objective);
  EXPECT_LT((all.trajectory.finalState() - lazy.trajectory.finalState()).norm(), 1e-6);
}

TEST(SolveSceneTask, ATargetThePlanCannotMeetIsSaidNotReachedWithItsDistance) {
  // The puck 4 away in T = 2 at |u| <= 2: within the conservative reach (2 sqrt(8) = 5.7), so
  // not refused, but the pusher must first cover the 2 to the puck (1 s), then pushes it at
  // half its speed (the projection shares the push): the puck gets 1, the best plan, and the
  // message says time was the limit.
  fesd::SceneTask task = pushingTask();
  task.bodies[1].target = Eigen::Vector2d(4.0, 0.0);
  task.bodies[1].target_weight = 100.0;
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 2;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  ASSERT_TRUE(outcome.solved()) << outcome.invalid << outcome.infeasible;
  EXPECT_EQ(outcome.status, fesd::SolveStatus::kTargetNotReached) << outcome.message;
  ASSERT_EQ(outcome.target_distances.size(), 3u);
  EXPECT_TRUE(std::isnan(outcome.target_distances[0]));  // the pusher has no target
  EXPECT_NEAR(outcome.target_distances[1], 3.0, 1e-3);
  EXPECT_NE(outcome.message.find("within the horizon at their speed bounds"), std::string::npos)
      << outcome.message;
  EXPECT_LT(outcome.report.iterations, 100) << outcome.message;
  EXPECT_NEAR(outcome.target_distances[1],
              (outcome.trajectory.finalState().segment<2>(2) - Eigen::Vector2d(4, 0)).norm(),
              1e-12);
  EXPECT_NE(outcome.message.find("body 'puck' ends"), std::string::npos) << outcome.message;
  EXPECT_TRUE(fesd::solvedItsNlp(outcome.status));  // still a plan to start from
  EXPECT_DOUBLE_EQ(fesd::targetTolerance(1000.0), 1e-3);
  EXPECT_DOUBLE_EQ(fesd::targetTolerance(1.0), 0.1);
}

TEST(SolveSceneTask, ATargetBeyondThePushersReachIsAnsweredAsFastAsAReachableOne) {
  // The showcase's object target at x = 1.2: no pusher placement reaches it (the workspace
  // bounds); cold solves aimed at it took 50-120 s, thousands of iterations.
  fesd::SceneSolveOptions options;
  const fesd::SceneOutcome outcome =
      fesd::solveSceneTask(fesd::manipulation_example::task(40, Eigen::Vector2d(1.2, 10.0)),
                           fesd::TaskLimits{}, options);
  ASSERT_TRUE(outcome.solved()) << outcome.invalid << outcome.infeasible;
  EXPECT_EQ(outcome.status, fesd::SolveStatus::kTargetNotReached) << outcome.message;
  EXPECT_LT(outcome.report.iterations, 150) << outcome.message;
  EXPECT_GT(outcome.target_distances[2], 0.5);
  EXPECT_LT(outcome.target_distances[2], 1.0);
  EXPECT_NE(outcome.message.find("out of the pushers' reach"), std::string::npos)
      << outcome.message;
}

TEST(SolveSceneTask, AnNlpBeyondTheMemoryLimitIsRefusedWithItsEstimate) {
  fesd::TaskLimits limits;
  limits.max_solver_mib = 0.01;
  const fesd::SceneOutcome refused =
      fesd::solveSceneTask(fesd_test::pushingTask(), limits, fesd::SceneSolveOptions{});
  EXPECT_NE(refused.invalid.find("the NLP is too large to solve here: about"), std::string::npos)
      << refused.invalid;
  EXPECT_NE(refused.invalid.find("> limits/max_solver_mib 0.01"), std::string::npos);
  EXPECT_EQ(refused.report.iterations, 0);
}

}  // namespace
