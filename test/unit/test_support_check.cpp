// Whether a plan only pushes bodies into their supports (planning/support_check.cpp): a pusher
// pushing a puck on a table (fesd_test::puckOnATable, along x at 0.2 for 2 s) from below its
// centre would lift it, level or from above it would not; a solve whose plan would lift it pushes
// it in the next round only as the table holds it.
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

TEST(SupportCheck, ASolveWhosePlanWouldLiftTheBodyPushesItOnlyAsTheSupportHoldsIt) {
  // A small pusher sliding on the table too (radius 0.02: its centre at 0.02) can push the puck
  // only from below its centre: the plan must keep the push's lift within the tolerance (here
  // by pushing while the contact's normal is nearly level, or not at all).
  fesd::SceneTask task = fesd_test::puckOnATable(0.02);
  task.scene.bodies()[0].radius = 0.02;
  task.bodies[1].target = Eigen::Vector3d(0.15, 0.0, 0.05);
  task.bodies[1].target_weight = 100.0;
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 2;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, {}, options);
  ASSERT_TRUE(outcome.solved()) << outcome.invalid << outcome.infeasible;
  EXPECT_EQ(outcome.held_on_support, std::vector<int>{1});
  EXPECT_EQ(outcome.supports, std::vector<int>({0, 0}));
  EXPECT_NE(outcome.message.find("would lift 'puck' off 'table'"), std::string::npos)
      << outcome.message;
  EXPECT_NE(outcome.message.find("pushes it only as 'table' holds it"), std::string::npos)
      << outcome.message;
  EXPECT_GE(outcome.pair_rounds, 2);
  // The answer's plan lifts it by at most half the tolerance, and its height never changed.
  const double lift = fesd::supportLifts(task, outcome.trajectory, outcome.modelled)[1];
  EXPECT_LE(lift, 0.5 * fesd::kSupportLiftTolerance * 0.05 * (1.0 + 1e-6));
  for (const Eigen::VectorXd& x : outcome.trajectory.states) {
    EXPECT_DOUBLE_EQ(task.scene.position(1, x).z(), 0.05);
  }
  for (const fesd::PairDecision& decision : outcome.decisions) {
    EXPECT_NE(task.scene.pairName(decision.pair), "puck/table");
  }
}

}  // namespace
