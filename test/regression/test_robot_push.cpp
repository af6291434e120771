// The shipped planar-arm push (examples/robot_scenes.h) planned end to end: the arm's spheres push
// the disc to its target to 1e-3, no modelled pair penetrates at any element boundary of the
// plan nor of its fine re-simulation, which ends where the plan does.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/scene_units.h"
#include "fesd_trajopt/solver/stopwatch.h"
#include "support/robot_files.h"
#include "support/scene_tasks.h"

namespace {

class RobotPush : public ::testing::TestWithParam<bool> {};

// Every pair in reach (false: the node's default for the arm's 9) succeeds, its plan what its
// re-simulation does. Lazy pairs (true) model the second hand sphere from round 2; its plans cut
// into the disc between stage points in the last interval (graze rounds shrink the cut from 1.4e-2
// to 1.2e-5 but do not close it) or pass through it inside an element: through the node's default
// request (the accuracy ladder) an answer it calls SUCCESS is accurate, else it says why not
// (measured: ACCURACY_NOT_MET, the disc 0.127 short; SUCCESS with a monotone warm barrier).
TEST_P(RobotPush, PlanarArmPushesTheDiscToItsTarget) {
  const fesd::SceneTask task = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  const fesd::Stopwatch stopwatch;
  fesd::SceneSolveOptions options = fesd_test::robotSolveOptions();
  options.lazy_pairs = GetParam();
  const fesd::SceneOutcome outcome = GetParam() ? fesd::solveToAccuracy(task, {}, options, 1e-2)
                                                : fesd::solveSceneTask(task, {}, options);
  const double seconds = stopwatch.wallSeconds();
  ASSERT_EQ(outcome.invalid, "");
  if (GetParam()) {
    EXPECT_LT(outcome.modelled.size(), 9u);
    if (outcome.status == fesd::SolveStatus::kSuccess) {
      EXPECT_TRUE(outcome.grazes.empty());
      EXPECT_LT(outcome.verification.error, 1e-2 * outcome.length_scale);
    } else {
      EXPECT_EQ(outcome.status, fesd::SolveStatus::kAccuracyNotMet) << outcome.message;
    }
    return;
  }
  ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  EXPECT_LT(outcome.target_distances[0], 1e-3 * outcome.length_scale);
  EXPECT_GT(outcome.boundary_gap, -1e-8);
  EXPECT_GT(outcome.verification.gap, -1e-6);
  EXPECT_LT(outcome.verification.error, 1e-2 * outcome.length_scale);  // measured 1.6e-5
  // The disc moved: some sphere pushed it.
  EXPECT_GT((outcome.trajectory.finalState().tail(2) - task.scene.bodies()[0].position).norm(),
            0.15);
  std::printf(
      "planar arm push (lazy pairs %d): %.2f s, %d Ipopt iterations, objective %.6g, %zu modelled "
      "pairs in %d rounds, target %.2e, boundary gap %.2e, verification error %.2e gap %.2e, "
      "pusher %s\n",
      GetParam(), seconds, outcome.report.iterations, outcome.report.objective,
      outcome.modelled.size(), outcome.pair_rounds, outcome.target_distances[0],
      outcome.boundary_gap, outcome.verification.error, outcome.verification.gap,
      task.scene.robot().spheres[outcome.pusher_sphere].name.c_str());
}

INSTANTIATE_TEST_SUITE_P(LazyAndAll, RobotPush, ::testing::Bool());

// The arm push in other length units (the same robot and disc with every length times k): one
// plan, its joints the same radians and the disc's path scaled; to the bit for a power of two,
// else the same NLP to rounding, which moves Ipopt's path (its free barrier) by a few iterations.
TEST(RobotPush, ThePlanarArmInMillimetresIsTheSamePlan) {
  const fesd::SceneTask task = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  const fesd::SceneSolveOptions options = fesd_test::robotSolveOptions();
  const fesd::SceneOutcome metres = fesd::solveSceneTask(task, {}, options);
  ASSERT_EQ(metres.status, fesd::SolveStatus::kSuccess) << metres.message;
  for (const double k : {4.0, 1000.0}) {
    SCOPED_TRACE(k);
    const fesd::SceneOutcome other = fesd::solveSceneTask(fesd::scaledTask(task, k), {}, options);
    ASSERT_EQ(other.status, fesd::SolveStatus::kSuccess) << other.message;
    if (k == 4.0) {
      EXPECT_EQ(other.report.iterations, metres.report.iterations);
    }
    EXPECT_LE(std::abs(other.report.iterations - metres.report.iterations),
              metres.report.iterations / 5);
    EXPECT_NEAR(other.length_scale, k * metres.length_scale, 1e-12 * k);
    ASSERT_EQ(other.trajectory.states.size(), metres.trajectory.states.size());
    const int nq = task.scene.numJoints();
    double joints = 0.0, disc = 0.0;
    for (size_t i = 0; i < metres.trajectory.states.size(); ++i) {
      const Eigen::VectorXd& a = other.trajectory.states[i];
      const Eigen::VectorXd& b = metres.trajectory.states[i];
      joints = std::max(joints, (a.head(nq) - b.head(nq)).cwiseAbs().maxCoeff());
      disc = std::max(disc, (a.tail(2) / k - b.tail(2)).cwiseAbs().maxCoeff());
    }
    EXPECT_LE(joints, k == 4.0 ? 0.0 : 1e-6);  // radians either way
    EXPECT_LE(disc, k == 4.0 ? 0.0 : 1e-6);
    EXPECT_NEAR(other.report.objective / (k * k), metres.report.objective,
                1e-8 * metres.report.objective);
    EXPECT_NEAR(other.verification.error / k, metres.verification.error,
                1e-3 * metres.verification.error);
  }
}

// The arm's disc as a bar of two spheres that turns (quasi-static pushing, the bar's own limit
// surface), through the node's default request: the arm pushes it to the disc's target and turns
// it by 0.3 rad, without penetration at any element boundary, verified to 1 % of the length scale.
TEST(RobotPush, PlanarArmBringsATurningBarToAPose) {
  fesd::Scene bar_scene(2);
  fesd::SceneBody bar{"bar", 0.04, Eigen::Vector2d(0.6, 0.0)};
  bar.spheres = {{"bar/sphere_0", Eigen::Vector3d(-0.05, 0.0, 0.0), 0.04},
                 {"bar/sphere_1", Eigen::Vector3d(0.05, 0.0, 0.0), 0.04}};
  fesd::turnAboutPressureCentre(bar, 0.0);
  bar_scene.bodies().push_back(bar);
  fesd::SceneTask task = fesd::taskOn(fesd::robotInScene(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")),
      Eigen::Vector3d(-0.6, 0.0, 0.0), bar_scene));
  task.bodies[0].target = Eigen::Vector2d(0.6, 0.2);
  task.bodies[0].target_weight = 100.0;
  task.bodies[0].target_yaw = 0.3;
  task.bodies[0].target_yaw_weight = 100.0;
  task.horizon = 2.0;
  task.num_intervals = 10;
  const fesd::Stopwatch stopwatch;
  const fesd::SceneOutcome outcome =
      fesd::solveToAccuracy(task, {}, fesd_test::robotSolveOptions(), 1e-2);
  ASSERT_EQ(outcome.invalid, "");
  ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  EXPECT_LT(outcome.target_distances[0], 1e-3 * outcome.length_scale);
  EXPECT_LT(outcome.target_yaw_distances[0], 1e-3);
  EXPECT_NEAR(task.scene.yaw(0, outcome.trajectory.finalState()), 0.3, 1e-3);
  EXPECT_GT(outcome.boundary_gap, -1e-8);
  EXPECT_LT(outcome.verification.error, 1e-2 * outcome.length_scale);
  EXPECT_GT(outcome.verification.gap, -1e-6);
  std::printf(
      "planar arm turns a bar: %.2f s, %d Ipopt iterations, target %.2e, yaw %.2e, verification "
      "error %.2e\n",
      stopwatch.wallSeconds(), outcome.report.iterations, outcome.target_distances[0],
      outcome.target_yaw_distances[0], outcome.verification.error);
}

}  // namespace

namespace {

// The shipped Panda push (59 spheres) with lazy pairs, planned without the re-simulation as the
// planning sweep times plans: the puck ends at its target, no sphere of the robot is inside the
// puck or the table at any element boundary (every pair in reach, modelled or checked), and the
// contact that pushes the puck is reported with its time.
// The 4 cm puck climbs the accuracy ladder (n_s 2 -> 3 -> 4, then more elements): each rung
// starts from the plan before, mapped onto its grid, whose interpolated stage points leave
// complementarity products up to 2.6. Polishing that plan's active set first: the last rung
// takes 42 Ipopt iterations; entering the homotopy at 1e-4 instead took 534.
TEST(RobotPush, PandasFinerRungsStartFromTheCoarserPlansActiveSet) {
  const fesd::SceneTask task =
      fesd::pandaSmallPuckTask(std::make_shared<const fesd::KinematicModel>(
          fesd_test::loadShippedRobot("panda_spherized.urdf")));
  fesd::SceneSolveOptions options = fesd_test::robotSolveOptions();  // as the node's defaults
  options.lazy_pairs = true;
  options.all_pairs_up_to = 32;
  options.ocp.discretization.num_elements = 3;
  options.verification.num_stages = 3;
  options.verification.num_elements = 6;
  const fesd::SceneOutcome outcome = fesd::solveToAccuracy(task, {}, options, 1e-2);
  ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  ASSERT_GE(outcome.refinements.size(), 2u) << outcome.message;
  for (size_t r = 1; r < outcome.refinements.size(); ++r) {
    EXPECT_TRUE(outcome.refinements[r].from_previous_plan) << outcome.refinements[r].change;
  }
  EXPECT_LE(outcome.report.iterations, 60) << outcome.message;
  EXPECT_LT(outcome.verification.error, 1e-2 * outcome.length_scale);
}

TEST(RobotPush, PandaPushesThePuckAcrossTheTable) {
  const fesd::SceneTask task = fesd::pandaPushTask(std::make_shared<const fesd::KinematicModel>(
      fesd_test::loadShippedRobot("panda_spherized.urdf")));
  const fesd::Stopwatch stopwatch;
  fesd::SceneSolveOptions options = fesd_test::robotSolveOptions();
  options.lazy_pairs = true;
  options.verify = false;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, {}, options);
  const double seconds = stopwatch.wallSeconds();
  ASSERT_EQ(outcome.invalid, "");
  ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  EXPECT_LT(outcome.target_distances[0], 1e-3);
  std::vector<fesd::ContactPair> in_reach;
  for (const fesd::PairDecision& decision : outcome.decisions) {
    if (decision.modelled || decision.checked) in_reach.push_back(decision.pair);
  }
  EXPECT_EQ(in_reach.size(), 117u);  // spheres on the puck and the table; the puck slides on it
  ASSERT_EQ(outcome.supports, std::vector<int>{0});
  const double gap = fesd::smallestBoundaryGap(task.scene, in_reach, outcome.trajectory);
  EXPECT_GT(gap, -1e-8);
  // The puck stays on the table at every element boundary.
  for (const Eigen::VectorXd& x : outcome.trajectory.states) {
    EXPECT_EQ(task.scene.position(0, x).z(), 0.05);
  }
  int puck_contacts = 0;
  for (const fesd::SwitchEvent& event : outcome.trajectory.switches) {
    const fesd::ContactPair& pair = outcome.modelled[event.constraint];
    if (pair.kind == fesd::ContactPair::Kind::kBody &&
        event.kind == fesd::SwitchEvent::Kind::kContact) {
      ++puck_contacts;
      EXPECT_GT(event.time, 0.0);
      EXPECT_LT(event.time, task.horizon);
    }
  }
  EXPECT_GE(puck_contacts, 1);
  std::printf(
      "panda push: %.2f s, %d Ipopt iterations, objective %.6g, %zu modelled pairs in %d "
      "rounds, target %.2e, boundary gap %.2e, pusher %s\n",
      seconds, outcome.report.iterations, outcome.report.objective, outcome.modelled.size(),
      outcome.pair_rounds, outcome.target_distances[0], gap,
      task.scene.robot().spheres[outcome.pusher_sphere].name.c_str());
}

}  // namespace
