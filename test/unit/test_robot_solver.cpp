// Robot tasks solved (scene/robot_solver.cpp): a refused task is not solved, joints driven to
// their targets without contact, a passive joint, a replan's warm start (also with lazy pairs),
// and the boundary gaps.
#include <cstdio>
#include <memory>

#include <gtest/gtest.h>

#include "fesd_trajopt/scene/robot_lazy_pairs.h"
#include "fesd_trajopt/scene/robot_scenes.h"
#include "fesd_trajopt/scene/robot_solver.h"
#include "support/robot_files.h"

namespace {

fesd::RobotTask armTask() {
  fesd::DiscScene discs(2);
  discs.obstacles().push_back({"post", 0.05, Eigen::Vector2d(0.0, 0.7)});
  fesd::RobotTask task(fesd::RobotScene(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")),
      Eigen::Vector3d::Zero(), discs));
  task.horizon = 1.0;
  task.num_intervals = 4;
  return task;
}

TEST(RobotSolver, RefusedTaskIsNotSolved) {
  fesd::RobotTask task = armTask();
  task.horizon = -1.0;
  const fesd::RobotOutcome outcome = fesd::solveRobotTask(task, {}, {});
  EXPECT_EQ(outcome.invalid, "the horizon must be in (0, 1e+04], got -1");
  EXPECT_TRUE(outcome.trajectory.states.empty());
}

TEST(RobotSolver, JointsReachTheirTargets) {
  fesd::RobotTask task = armTask();
  task.joints[1].target = 0.5;
  task.joints[1].target_weight = 100.0;
  const fesd::RobotOutcome outcome = fesd::solveRobotTask(task, {}, {});
  ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  EXPECT_LT(outcome.joint_target_distances[1], 1e-3);
  EXPECT_TRUE(std::isnan(outcome.joint_target_distances[0]));
  EXPECT_GT(outcome.boundary_gap, 0.0);
  EXPECT_LT(outcome.verification_error, 1e-6);
}

TEST(RobotSolver, APassiveJointTurnsOnlyWhileItsLinkIsPushed) {
  // The shipped arm push with the wrist passive: shoulder and elbow push the disc with the
  // hand, whose reaction alone turns the wrist.
  fesd::RobotTask task = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  task.joints[2].passive = true;
  EXPECT_EQ(fesd::jointSpeedLimit(task, 2), 0.0);
  fesd::RobotSolveOptions options;
  options.ocp.discretization.num_elements = 2;
  const fesd::RobotOutcome outcome = fesd::solveRobotTask(task, {}, options);
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
      outcome.target_distances[0], outcome.verification_error);
}

TEST(RobotSolver, AReplanWarmStartsFromTheLastPlanWhenItsStructureFits) {
  // The arm push, then the disc's target moved by 1 cm: the same NLP, started from the last
  // solution, ends in that plan's local optimum, here no worse than the cold solve's (moves of
  // 2 cm let the cold solve find a cheaper one). A longer horizon changes the structure: cold,
  // with the reason.
  const auto robot =
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf"));
  fesd::RobotSolveOptions options;
  options.ocp.discretization.num_elements = 2;
  fesd::RobotTask task = fesd::planarArmPushTask(robot);
  const fesd::RobotOutcome first = fesd::solveRobotTask(task, {}, options);
  ASSERT_EQ(first.status, fesd::SolveStatus::kSuccess) << first.message;
  EXPECT_EQ(first.start, fesd::OcpStart::kGuess);
  EXPECT_EQ(first.sizes.variables, static_cast<int>(first.report.solution.size()));

  task.bodies[0].target(1) += 0.01;
  const fesd::RobotOutcome cold = fesd::solveRobotTask(task, {}, options);
  options.previous = &first;
  const fesd::RobotOutcome warm = fesd::solveRobotTask(task, {}, options);
  ASSERT_EQ(warm.status, fesd::SolveStatus::kSuccess) << warm.message;
  EXPECT_EQ(warm.start, fesd::OcpStart::kPrevious);
  EXPECT_TRUE(warm.warm_started);
  EXPECT_FALSE(first.warm_started);
  EXPECT_EQ(warm.cold_start_reason, "");
  EXPECT_LT(warm.target_distances[0], 1e-3);
  EXPECT_LT(warm.report.iterations, cold.report.iterations / 2);
  EXPECT_LT(warm.report.objective, cold.report.objective * (1.0 + 1e-3));
  EXPECT_LT(warm.verification_error, 1e-4);

  fesd::RobotTask longer = task;
  longer.horizon *= 1.25;
  const fesd::RobotOutcome refused = fesd::solveRobotTask(longer, {}, options);
  ASSERT_TRUE(fesd::solvedItsNlp(refused.status)) << refused.message;
  EXPECT_EQ(refused.start, fesd::OcpStart::kGuess);
  EXPECT_FALSE(refused.warm_started);
  EXPECT_EQ(refused.cold_start_reason.rfind("the horizons differ", 0), 0u)
      << refused.cold_start_reason;
  std::printf("arm push replanned: cold %d, warm %d Ipopt iterations; objectives %.8g, %.8g\n",
              cold.report.iterations, warm.report.iterations, cold.report.objective,
              warm.report.objective);
}

TEST(RobotSolver, ALazyReplanStartsWithThePairsTheLastPlanEndedWith) {
  // With lazy pairs the first round models what the guess calls for; a warm start's first round
  // models the previous plan's pairs instead, so that its NLP matches and the warm start applies.
  fesd::RobotSolveOptions options;
  options.ocp.discretization.num_elements = 2;
  options.lazy_pairs = true;
  fesd::RobotTask task = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  const fesd::RobotOutcome first = fesd::solveRobotTask(task, {}, options);
  ASSERT_TRUE(fesd::solvedItsNlp(first.status)) << first.message;
  task.bodies[0].target(1) += 0.01;
  options.previous = &first;
  const fesd::RobotOutcome warm = fesd::solveRobotTask(task, {}, options);
  ASSERT_TRUE(fesd::solvedItsNlp(warm.status)) << warm.message;
  EXPECT_TRUE(warm.warm_started) << warm.cold_start_reason;
  int from_previous = 0;
  for (const fesd::RobotPairDecision& decision : warm.decisions) {
    from_previous += decision.reason == "modelled in the previous solution (warm start)";
  }
  EXPECT_EQ(from_previous, static_cast<int>(first.structure.modelled_pairs.size()));
  // Every pair in reach reports its smallest gap: the modelled ones' the plan holds >= 0, the
  // checked ones' beyond the margin (else they would have been modelled).
  int checked = 0;
  for (const fesd::RobotPairDecision& decision : warm.decisions) {
    if (decision.modelled) {
      EXPECT_GE(decision.min_distance, -1e-9) << decision.reason;
    }
    if (!decision.checked) continue;
    ++checked;
    EXPECT_GE(decision.min_distance,
              options.pair_margin * fesd::robotPairSize(task.scene, decision.pair));
  }
  EXPECT_GT(checked, 0);
  std::printf(
      "lazy arm push replanned: %d pairs from the last plan, %d rounds, %d iterations "
      "(first plan %d)\n",
      from_previous, warm.pair_rounds, warm.report.iterations, first.report.iterations);
}

TEST(RobotSolver, LazyPairsModelEveryPairOfATaskWithFewInReach) {
  fesd::RobotSolveOptions options;
  options.ocp.discretization.num_elements = 2;
  options.verify = false;
  options.lazy_pairs = true;
  options.all_pairs_up_to = 9;  // the arm push has 9 pairs in reach
  const fesd::RobotTask task = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  const fesd::RobotOutcome all = fesd::solveRobotTask(task, {}, options);
  ASSERT_EQ(all.status, fesd::SolveStatus::kSuccess) << all.message;
  EXPECT_EQ(all.modelled.size(), 9u);
  EXPECT_EQ(all.pair_rounds, 1);
  options.all_pairs_up_to = 8;
  const fesd::RobotOutcome lazy = fesd::solveRobotTask(task, {}, options);
  ASSERT_EQ(lazy.status, fesd::SolveStatus::kSuccess) << lazy.message;
  EXPECT_LT(lazy.modelled.size(), 9u);
}

TEST(RobotSolver, AFreeBodyWithTwoSpheresIsPushedAsOneRigidBody) {
  // The shipped arm push with the disc replaced by a bar of two spheres across the push: the
  // hand pushes whichever sphere it meets and the other follows.
  const fesd::RobotTask shipped = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  fesd::DiscScene discs = shipped.scene.discs();
  discs.bodies()[0] = {"bar", 0.08, Eigen::Vector2d(0.6, 0.0), false};
  const std::vector<fesd::FreeBodySphere> bar = {
      {"bar/sphere_0", Eigen::Vector3d(-0.04, 0.0, 0.0), 0.04},
      {"bar/sphere_1", Eigen::Vector3d(0.04, 0.0, 0.0), 0.04}};
  fesd::RobotTask task(
      fesd::RobotScene(shipped.scene.robotPointer(), shipped.scene.initialJoints(), discs, {bar}));
  task.bodies = shipped.bodies;
  task.horizon = shipped.horizon;
  task.num_intervals = shipped.num_intervals;
  const fesd::RobotOutcome outcome = fesd::solveRobotTask(task, {}, {});
  ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  EXPECT_LT(outcome.target_distances[0], 1e-3);
  EXPECT_GT(outcome.boundary_gap, -1e-6 * 0.07);
  EXPECT_GT(outcome.verification_gap, -1e-6 * 0.07);
  EXPECT_LT(outcome.verification_error, 1e-2);
  // The pushing pair is one of the bar's spheres against a hand sphere.
  int bar_pairs = 0;
  for (const fesd::RobotPair& pair : outcome.modelled) {
    const std::string name = task.scene.pairName(pair);
    bar_pairs += name.rfind("bar/sphere_", 0) == 0 && name.find("/hand/") != std::string::npos;
  }
  EXPECT_GT(bar_pairs, 0);
  std::printf(
      "two-sphere bar pushed: %s, %d Ipopt iterations, objective %.10g, bar %.2e from "
      "its target, boundary gap %.2e, verification %.2e\n",
      fesd::statusName(outcome.status).c_str(), outcome.report.iterations, outcome.report.objective,
      outcome.target_distances[0], outcome.boundary_gap, outcome.verification_error);
}

TEST(RobotSolver, SmallestBoundaryGap) {
  const fesd::RobotTask task = armTask();
  std::vector<fesd::RobotPair> tip;
  for (const fesd::RobotPair& pair : task.scene.allPairs()) {
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
