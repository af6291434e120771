// Whether a plan only pushes bodies into their supports (planning/support_check.cpp): a pusher
// pushing a puck on a table (fesd_test::puckOnATable, along x at 0.2 for 2 s) from below its
// centre would lift it, level or from above it would not; a solve whose plan would lift it lets
// the puck float and models it against the table.
#include "fesd_trajopt/planning/support_check.h"

#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/planning/scene_solver.h"
#include "support/scene_tasks.h"

namespace {

double puckLift(double z) {
  const fesd::SceneTask task = fesd_test::puckOnATable(z);
  Eigen::VectorXd push = Eigen::VectorXd::Zero(3);
  push(0) = 0.2;
  const fesd::SceneOutcome run = fesd::simulateSceneTask(task, {push}, {}, {});
  EXPECT_EQ(run.status, fesd::SolveStatus::kSuccess) << run.message;
  EXPECT_EQ(run.supports, std::vector<int>({-1, 0}));
  // The puck slid: its height held, its x moved.
  const Eigen::VectorXd end = run.trajectory.finalState();
  EXPECT_DOUBLE_EQ(task.scene.position(1, end).z(), 0.05);
  EXPECT_GT(task.scene.position(1, end).x(), 0.05);
  return fesd::supportLifts(task, run.trajectory, run.modelled)[1];
}

TEST(SupportCheck, APushFromBelowTheCentreWouldLiftTheBody) {
  EXPECT_GT(puckLift(0.035), 1e-3);
  EXPECT_EQ(puckLift(0.05), 0.0);  // level: the force is along the table
  EXPECT_EQ(puckLift(0.07), 0.0);  // from above: it presses the puck into the table
}

TEST(SupportCheck, ASolveWhosePlanWouldLiftTheBodyLetsItFloatAndModelsThePair) {
  // A small pusher sliding on the table too (radius 0.02: its centre at 0.02) pushes the puck
  // from below its centre.
  fesd::SceneTask task = fesd_test::puckOnATable(0.02);
  task.scene.bodies()[0].radius = 0.02;
  task.bodies[1].target = Eigen::Vector3d(0.15, 0.0, 0.05);
  task.bodies[1].target_weight = 100.0;
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 2;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, {}, options);
  ASSERT_TRUE(outcome.solved()) << outcome.invalid << outcome.infeasible;
  EXPECT_EQ(outcome.released_supports, std::vector<int>{1});
  EXPECT_EQ(outcome.supports, std::vector<int>({0, -1}));
  EXPECT_NE(outcome.message.find("would lift 'puck' off 'table'"), std::string::npos)
      << outcome.message;
  bool modelled = false;
  for (const fesd::PairDecision& decision : outcome.decisions) {
    modelled =
        modelled || (task.scene.pairName(decision.pair) == "puck/table" && decision.modelled);
  }
  EXPECT_TRUE(modelled);
  EXPECT_GE(outcome.pair_rounds, 2);
}

}  // namespace
