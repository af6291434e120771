// The scene entry points: one call from a task to a full-scene trajectory, for planning and for
// simulation, refusing what must not be solved. With a robot: joints driven to their targets
// without contact, a passive joint, a replan's warm start (also with lazy pairs), and the
// boundary gaps.
#include <cmath>
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/lazy_pairs.h"
#include "support/robot_files.h"
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

TEST(VerificationOptions, AreFinerThanTheSolveAndStopHopelessStepsEarly) {
  fesd::DiscretizationOptions configured;
  configured.num_stages = 3;
  configured.num_elements = 6;
  fesd::OcpOptions solve;
  solve.discretization.num_stages = 4;
  solve.discretization.interval_elements = {2, 5, 3};
  solve.homotopy.ipopt.linear_solver = fesd::kLdltSolver;
  const fesd::SimulationOptions fine = fesd::verificationOptions(configured, solve, 7.0);
  EXPECT_EQ(fine.discretization.num_stages, 4);
  EXPECT_EQ(fine.discretization.num_elements, 10);  // twice the solve's most
  EXPECT_EQ(fine.wall_time_budget, 7.0);
  EXPECT_EQ(fine.homotopy.ipopt.linear_solver, fesd::kLdltSolver);
  EXPECT_FALSE(fine.refine_by_homotopy);
  EXPECT_TRUE(fine.split_before_homotopy);
  EXPECT_EQ(fine.homotopy.ipopt.max_iterations, fesd::kVerificationNlpIterations);
  EXPECT_EQ(fine.retry_homotopy.ipopt.max_iterations, fesd::kVerificationNlpIterations);
  EXPECT_LT(fesd::kVerificationNlpIterations, fesd::IpoptSettings{}.max_iterations);
  // A failing homotopy gives way to its fallbacks: the retry at once, the retry itself to twice
  // the elements and fixed steps after two failures in a row.
  EXPECT_EQ(fine.homotopy.max_consecutive_failures, 1);
  EXPECT_EQ(fine.retry_homotopy.max_consecutive_failures, 2);
  EXPECT_EQ(fesd::verificationOptions(configured, solve, -1.0).wall_time_budget, 0.0);
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
  EXPECT_LT(pruned.verification.error, 1e-6);

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

TEST(SolveSceneTask, APushAlongAWallThePusherCannotFollowEndsAgainstTheWallFast) {
  // The pusher is wider than the puck's gap to the wall: no push keeps the puck off the wall.
  // Aimed straight at the target the solver chased it for thousands of iterations.
  const fesd::SceneTask task = fesd_test::pushAlongAWall();
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 3;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  ASSERT_TRUE(outcome.solved()) << outcome.invalid << outcome.infeasible;
  EXPECT_EQ(outcome.status, fesd::SolveStatus::kTargetNotReached) << outcome.message;
  EXPECT_NEAR(outcome.target_distances[1], 0.05, 1e-3);
  const Eigen::VectorXd end = outcome.trajectory.finalState();
  EXPECT_NEAR(end(3), -0.05, 1e-6);  // against the wall
  EXPECT_GT(end(2), 3.0 - 1e-3);
  EXPECT_NE(outcome.message.find("out of the pushers' reach"), std::string::npos)
      << outcome.message;
  // Aimed at the wall as a reachable task: a few hundred iterations (the solver chasing the
  // target itself took thousands).
  EXPECT_LT(outcome.report.iterations, 300) << outcome.message;
  std::printf("push along a wall: %s in %d iterations\n", fesd::statusName(outcome.status).c_str(),
              outcome.report.iterations);
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

namespace {

fesd::SceneTask armTask() {
  fesd::Scene discs(2);
  discs.obstacles().push_back({"post", 0.05, Eigen::Vector2d(0.0, 0.7)});
  fesd::SceneTask task = fesd::taskOn(fesd::robotInScene(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")),
      Eigen::Vector3d::Zero(), discs));
  task.horizon = 1.0;
  task.num_intervals = 4;
  return task;
}

TEST(SolveSceneTaskWithARobot, RefusedTaskIsNotSolved) {
  fesd::SceneTask task = armTask();
  task.horizon = -1.0;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, {}, fesd_test::robotSolveOptions());
  EXPECT_EQ(outcome.invalid, "the horizon must be in (0, 1e+04], got -1");
  EXPECT_TRUE(outcome.trajectory.states.empty());
}

TEST(SolveSceneTaskWithARobot, JointsReachTheirTargets) {
  fesd::SceneTask task = armTask();
  task.joints[1].target = 0.5;
  task.joints[1].target_weight = 100.0;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, {}, fesd_test::robotSolveOptions());
  ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  EXPECT_LT(outcome.joint_target_distances[1], 1e-3);
  EXPECT_TRUE(std::isnan(outcome.joint_target_distances[0]));
  EXPECT_GT(outcome.boundary_gap, 0.0);
  EXPECT_LT(outcome.verification.error, 1e-6);
}

TEST(SolveSceneTaskWithARobot, APassiveJointTurnsOnlyWhileItsLinkIsPushed) {
  // The shipped arm push with the wrist passive: shoulder and elbow push the disc with the
  // hand, whose reaction alone turns the wrist.
  fesd::SceneTask task = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  task.joints[2].passive = true;
  EXPECT_EQ(fesd::jointSpeedLimit(task, 2), 0.0);
  fesd::SceneSolveOptions options = fesd_test::robotSolveOptions();
  options.ocp.discretization.num_elements = 2;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, {}, options);
  ASSERT_TRUE(fesd::solvedItsNlp(outcome.status)) << outcome.message;
  const fesd::Trajectory& plan = outcome.trajectory;
  for (const Eigen::VectorXd& u : plan.controls) EXPECT_EQ(u(2), 0.0);
  int pushed_elements = 0;
  double turned = 0.0;
  for (size_t e = 0; e < plan.elements.size(); ++e) {
    const double wrist_motion = std::abs(plan.states[e + 1](2) - plan.states[e](2));
    turned += wrist_motion;
    if (plan.elements[e].stage_multipliers.maxCoeff() <= 1e-9) {
      EXPECT_LT(wrist_motion, 1e-9) << "element " << e;
    } else {
      ++pushed_elements;
    }
  }
  EXPECT_GT(pushed_elements, 0);
  EXPECT_GT(turned, 1e-3);  // the push turned the wrist
  EXPECT_GT(outcome.boundary_gap, -1e-9);
  std::printf(
      "passive wrist: %s, turned %.4f rad over %d pushed elements, disc %.2e from its "
      "target, verification %.2e\n",
      fesd::statusName(outcome.status).c_str(), turned, pushed_elements,
      outcome.target_distances[0], outcome.verification.error);
}

TEST(SolveSceneTaskWithARobot, AReplanWarmStartsFromTheLastPlanWhenItsStructureFits) {
  // The arm push, then the disc's target moved by 1 cm: the same NLP, started from the last
  // solution, ends in that plan's local optimum, here no worse than the cold solve's (moves of
  // 2 cm let the cold solve find a cheaper one). A longer horizon changes the structure: cold,
  // with the reason.
  const auto robot =
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf"));
  fesd::SceneSolveOptions options = fesd_test::robotSolveOptions();
  options.ocp.discretization.num_elements = 2;
  fesd::SceneTask task = fesd::planarArmPushTask(robot);
  const fesd::SceneOutcome first = fesd::solveSceneTask(task, {}, options);
  ASSERT_EQ(first.status, fesd::SolveStatus::kSuccess) << first.message;
  EXPECT_EQ(first.start, fesd::OcpStart::kGuess);
  EXPECT_EQ(first.sizes.variables, static_cast<int>(first.report.solution.size()));

  task.bodies[0].target(1) += 0.01;
  const fesd::SceneOutcome cold = fesd::solveSceneTask(task, {}, options);
  options.previous = &first;
  const fesd::SceneOutcome warm = fesd::solveSceneTask(task, {}, options);
  ASSERT_EQ(warm.status, fesd::SolveStatus::kSuccess) << warm.message;
  EXPECT_EQ(warm.start, fesd::OcpStart::kPrevious);
  EXPECT_TRUE(warm.warm_started);
  EXPECT_FALSE(first.warm_started);
  EXPECT_EQ(warm.cold_start_reason, "");
  EXPECT_LT(warm.target_distances[0], 1e-3);
  EXPECT_LT(warm.report.iterations, cold.report.iterations / 2);
  EXPECT_LT(warm.report.objective, cold.report.objective * (1.0 + 1e-3));
  EXPECT_LT(warm.verification.error, 1e-4);

  fesd::SceneTask longer = task;
  longer.horizon *= 1.25;
  const fesd::SceneOutcome refused = fesd::solveSceneTask(longer, {}, options);
  ASSERT_TRUE(fesd::solvedItsNlp(refused.status)) << refused.message;
  EXPECT_EQ(refused.start, fesd::OcpStart::kGuess);
  EXPECT_FALSE(refused.warm_started);
  EXPECT_EQ(refused.cold_start_reason.rfind("the horizons differ", 0), 0u)
      << refused.cold_start_reason;
  std::printf("arm push replanned: cold %d, warm %d Ipopt iterations; objectives %.8g, %.8g\n",
              cold.report.iterations, warm.report.iterations, cold.report.objective,
              warm.report.objective);
}

TEST(SolveSceneTaskWithARobot, ALazyReplanStartsWithThePairsTheLastPlanEndedWith) {
  // With lazy pairs the first round models what the guess calls for; a warm start's first round
  // models the previous plan's pairs instead, so that its NLP matches and the warm start applies.
  fesd::SceneSolveOptions options = fesd_test::robotSolveOptions();
  options.ocp.discretization.num_elements = 2;
  options.lazy_pairs = true;
  fesd::SceneTask task = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  const fesd::SceneOutcome first = fesd::solveSceneTask(task, {}, options);
  ASSERT_TRUE(fesd::solvedItsNlp(first.status)) << first.message;
  task.bodies[0].target(1) += 0.01;
  options.previous = &first;
  const fesd::SceneOutcome warm = fesd::solveSceneTask(task, {}, options);
  ASSERT_TRUE(fesd::solvedItsNlp(warm.status)) << warm.message;
  EXPECT_TRUE(warm.warm_started) << warm.cold_start_reason;
  int from_previous = 0;
  for (const fesd::PairDecision& decision : warm.decisions) {
    from_previous += decision.reason == "modelled in the previous solution (warm start)";
  }
  EXPECT_EQ(from_previous, static_cast<int>(first.structure.modelled_pairs.size()));
  // Every pair in reach reports its smallest gap: the modelled ones' the plan holds >= 0, the
  // checked ones' beyond the margin (else they would have been modelled).
  int checked = 0;
  for (const fesd::PairDecision& decision : warm.decisions) {
    if (decision.modelled) {
      EXPECT_GE(decision.min_distance, -1e-9) << decision.reason;
    }
    if (!decision.checked) continue;
    ++checked;
    EXPECT_GE(decision.min_distance, options.pair_margin * task.scene.pairSize(decision.pair));
  }
  EXPECT_GT(checked, 0);
  std::printf(
      "lazy arm push replanned: %d pairs from the last plan, %d rounds, %d iterations "
      "(first plan %d)\n",
      from_previous, warm.pair_rounds, warm.report.iterations, first.report.iterations);
}

TEST(SolveSceneTaskWithARobot, LazyPairsModelEveryPairOfATaskWithFewInReach) {
  fesd::SceneSolveOptions options = fesd_test::robotSolveOptions();
  options.ocp.discretization.num_elements = 2;
  options.verify = false;
  options.lazy_pairs = true;
  options.all_pairs_up_to = 9;  // the arm push has 9 pairs in reach
  const fesd::SceneTask task = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  const fesd::SceneOutcome all = fesd::solveSceneTask(task, {}, options);
  ASSERT_EQ(all.status, fesd::SolveStatus::kSuccess) << all.message;
  EXPECT_EQ(all.modelled.size(), 9u);
  EXPECT_EQ(all.pair_rounds, 1);
  options.all_pairs_up_to = 8;
  const fesd::SceneOutcome lazy = fesd::solveSceneTask(task, {}, options);
  ASSERT_TRUE(lazy.solved()) << lazy.invalid << lazy.infeasible;
  EXPECT_LT(lazy.modelled.size(), 9u);
}

TEST(SolveSceneTaskWithARobot, AFreeBodyWithTwoSpheresIsPushedAsOneRigidBody) {
  // The shipped arm push with the disc replaced by a bar of two spheres across the push: the
  // hand pushes whichever sphere it meets and the other follows.
  const fesd::SceneTask shipped = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  fesd::Scene scene = shipped.scene;
  scene.bodies()[0] = {"bar",
                       0.08,
                       Eigen::Vector2d(0.6, 0.0),
                       false,
                       {{"bar/sphere_0", Eigen::Vector3d(-0.04, 0.0, 0.0), 0.04},
                        {"bar/sphere_1", Eigen::Vector3d(0.04, 0.0, 0.0), 0.04}}};
  fesd::SceneTask task = fesd::taskOn(scene);
  task.bodies = shipped.bodies;
  task.horizon = shipped.horizon;
  task.num_intervals = shipped.num_intervals;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, {}, fesd_test::robotSolveOptions());
  ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  EXPECT_LT(outcome.target_distances[0], 1e-3);
  EXPECT_GT(outcome.boundary_gap, -1e-6 * 0.07);
  EXPECT_GT(outcome.verification.gap, -1e-6 * 0.07);
  EXPECT_LT(outcome.verification.error, 1e-2);
  // The pushing pair is one of the bar's spheres against a hand sphere.
  int bar_pairs = 0;
  for (const fesd::ContactPair& pair : outcome.modelled) {
    const std::string name = task.scene.pairName(pair);
    bar_pairs += name.rfind("bar/sphere_", 0) == 0 && name.find("/hand/") != std::string::npos;
  }
  EXPECT_GT(bar_pairs, 0);
  std::printf(
      "two-sphere bar pushed: %s, %d Ipopt iterations, objective %.10g, bar %.2e from "
      "its target, boundary gap %.2e, verification %.2e\n",
      fesd::statusName(outcome.status).c_str(), outcome.report.iterations, outcome.report.objective,
      outcome.target_distances[0], outcome.boundary_gap, outcome.verification.error);
}

TEST(SolveSceneTaskWithARobot, SmallestBoundaryGap) {
  const fesd::SceneTask task = armTask();
  std::vector<fesd::ContactPair> tip;
  for (const fesd::ContactPair& pair : task.scene.allPairs()) {
    if (task.scene.pairName(pair) == "hand/sphere_1/post") tip.push_back(pair);
  }
  ASSERT_EQ(tip.size(), 1u);
  fesd::Trajectory trajectory;
  trajectory.states = {task.scene.initialState(), Eigen::Vector3d(M_PI / 2, 0.0, 0.0)};
  // At q = 0 the tip (0.9, 0) is sqrt(0.81 + 0.49) from the post; turned up it is at (0, 0.9),
  // 0.2 away: the gaps less the radii 0.08.
  EXPECT_NEAR(fesd::smallestBoundaryGap(task.scene, tip, trajectory), 0.2 - 0.08, 1e-12);
}

}  // namespace

/// A replan holds the grazes the plan before held: the closed loop's, 3 intervals on and on the
/// rest of that grid, in the intervals still to come, moved to its own intervals and elements;
/// the node's, on the same grid, as they were.
TEST(HoldWhatThePlanBeforeHeld, AReplanThatStartsLaterHoldsTheRestMovedToItsIntervals) {
  const fesd::ContactPair a{0, fesd::ContactPair::Kind::kBody, 1};
  const fesd::ContactPair b{2, fesd::ContactPair::Kind::kBody, 1};
  fesd::SceneOutcome previous;
  previous.structure.intervals = 6;
  previous.structure.horizon = 3.0;
  previous.structure.stages = 2;
  previous.structure.interval_elements = {2, 2, 3, 2, 2, 2};
  previous.held_grazes = {{a, 1}, {a, 4}, {b, 5}};
  fesd::Graze early, late;
  early.pair = late.pair = a;
  early.interval = 1;
  early.element = 3;
  late.interval = 4;
  late.element = 10;  // the second of interval 4 (9 elements before it)
  late.fraction = 0.3;
  late.time = 2.2;
  previous.guard_points = {early, late};
  fesd::SceneTask task = fesd_test::pushingTask();
  task.num_intervals = 3;
  task.horizon = 1.5;
  fesd::OcpOptions ocp;
  ocp.discretization.num_stages = 2;
  ocp.discretization.interval_elements = {2, 2, 2};
  fesd::SceneOutcome replan;
  fesd::holdWhatThePlanBeforeHeld(previous, task, ocp, replan);
  EXPECT_EQ(replan.held_grazes, (std::vector<fesd::PairInterval>{{a, 1}, {b, 2}}));
  ASSERT_EQ(replan.guard_points.size(), 1u);
  EXPECT_EQ(replan.guard_points[0].interval, 1);
  EXPECT_EQ(replan.guard_points[0].element, 3);
  EXPECT_DOUBLE_EQ(replan.guard_points[0].fraction, 0.3);
  EXPECT_NEAR(replan.guard_points[0].time, 0.7, 1e-12);
  // Finer than the rest of that grid: the grazes held, their points (on other elements) not.
  ocp.discretization.interval_elements = {3, 3, 3};
  fesd::SceneOutcome finer;
  fesd::holdWhatThePlanBeforeHeld(previous, task, ocp, finer);
  EXPECT_EQ(finer.held_grazes, (std::vector<fesd::PairInterval>{{a, 1}, {b, 2}}));
  EXPECT_TRUE(finer.guard_points.empty());
  // The node's replan of the same request: everything as it was.
  task.num_intervals = 6;
  task.horizon = 3.0;
  ocp.discretization.interval_elements = previous.structure.interval_elements;
  fesd::SceneOutcome same;
  fesd::holdWhatThePlanBeforeHeld(previous, task, ocp, same);
  EXPECT_EQ(same.held_grazes, previous.held_grazes);
  ASSERT_EQ(same.guard_points.size(), 2u);
  EXPECT_EQ(same.guard_points[1].element, 10);
}
