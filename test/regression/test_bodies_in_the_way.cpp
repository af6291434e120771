// Bodies in the way of a push (lazy contact pairs, the push plan's chains): the answer models
// every pair the motion meets, and a fine re-simulation of its controls with every pair in
// reach modelled neither penetrates anything nor departs from it.
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/planning_scenes.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/pair_check.h"
#include "support/scene_tasks.h"

namespace {

namespace ps = fesd::planning_scenes;

/// A pusher (R = 0.5, |u| <= 4) at (-2, 0), a puck (R = 0.5) to be pushed from the origin to
/// (3, 0) in T = 2 on 20 intervals, and passive discs (R = 0.5) where given.
ps::PlanningScene pushThrough(const std::vector<Eigen::Vector2d>& discs) {
  ps::PlanningScene scene;
  scene.task = fesd_test::pushAlongX();
  fesd::SceneTask& task = scene.task;
  for (size_t i = 0; i < discs.size(); ++i) {
    task.scene.bodies().push_back({"disc_" + std::to_string(i), 0.5, discs[i], false});
    task.bodies.emplace_back();
  }
  scene.pushed = 1;
  return scene;
}

fesd::SceneSolveOptions options() {
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 3;
  return options;
}

fesd::SimulationOptions fine() {
  fesd::SimulationOptions fine;
  fine.discretization.num_stages = 3;
  fine.discretization.num_elements = 6;
  return fine;
}

bool modelled(const fesd::SceneOutcome& outcome, const fesd::SceneTask& task,
              const std::string& name) {
  for (const fesd::PairDecision& d : outcome.decisions) {
    if (task.scene.pairName(d.pair) == name) return d.modelled;
  }
  return false;
}

/// SUCCESS with the target met, no penetration at the plan's element boundaries, and the
/// all-pairs re-simulation without penetration and close to the plan.
void expectMetAndPhysical(const ps::PlanningRun& run, double verification_tolerance) {
  ASSERT_EQ(run.outcome.status, fesd::SolveStatus::kSuccess) << run.outcome.message;
  EXPECT_LT(run.target_distance, 1e-3);
  EXPECT_GT(run.plan_gap, -1e-6);
  ASSERT_EQ(run.verification.status, fesd::SolveStatus::kSuccess);
  EXPECT_GT(run.verification_gap, -1e-6);
  EXPECT_LT(run.verification.error, verification_tolerance);
}

TEST(BodiesInTheWay, ADiscThePuckClipsIsModelledAndShovedAside) {
  const ps::PlanningScene scene = pushThrough({Eigen::Vector2d(1.5, 0.8)});
  const ps::PlanningRun run = ps::runScene(scene, options(), fine());
  expectMetAndPhysical(run, 1e-3);
  EXPECT_TRUE(modelled(run.outcome, scene.task, "puck/disc_0"));
  const Eigen::VectorXd end = run.outcome.trajectory.finalState();
  EXPECT_GT((end.tail<2>() - Eigen::Vector2d(1.5, 0.8)).norm(), 0.05);  // it was shoved
}

TEST(BodiesInTheWay, ADiscPushedIntoAThirdOneModelsTheWholeChain) {
  const ps::PlanningScene scene =
      pushThrough({Eigen::Vector2d(1.2, 0.3), Eigen::Vector2d(2.4, 0.6)});
  const ps::PlanningRun run = ps::runScene(scene, options(), fine());
  expectMetAndPhysical(run, 1e-2);
  EXPECT_TRUE(modelled(run.outcome, scene.task, "puck/disc_0"));
  EXPECT_TRUE(modelled(run.outcome, scene.task, "disc_0/disc_1"));
  const Eigen::VectorXd end = run.outcome.trajectory.finalState();
  EXPECT_GT((end.tail<2>() - Eigen::Vector2d(2.4, 0.6)).norm(), 0.05);  // the third one moved
}

TEST(BodiesInTheWay, APairTheFirstRoundMissedIsAddedAndSolvedAgain) {
  // Cluttered seed 0: a pusher and a puck among 12 passive discs and 6 obstacles; the first
  // round's answer comes within the margin of a pair the first guess did not need.
  const ps::PlanningScene scene = ps::clutteredScene(0);
  const ps::PlanningRun run = ps::runScene(scene, options(), fine());
  expectMetAndPhysical(run, 1e-2);
  EXPECT_GE(run.outcome.pair_rounds, 2);
  EXPECT_NE(run.outcome.message.find("round 2 added"), std::string::npos) << run.outcome.message;
  for (const fesd::PairDecision& d : run.outcome.decisions) {
    if (d.checked) {
      EXPECT_GT(d.min_distance, 0.1 * scene.task.scene.pairSize(d.pair));
    }
  }
}

}  // namespace
