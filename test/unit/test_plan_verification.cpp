// The verification of a plan (planning/plan_verification.cpp): interval boundaries, a solved push
// verified interval by interval and open loop, and grazes between stage points.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/discretization/butcher_tableau.h"
#include "fesd_trajopt/planning/plan_verification.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "support/scene_tasks.h"

namespace {

/// A pusher (R = 0.5) passing a puck (R = 0.5) at the origin in one element of length 1 on the
/// parabola (-1 + 2t, 1.2 - 0.96 t (1 - t)): clear at the start, the Radau stage points (1/3, 1)
/// and the end, 0.04 deep into the puck at t = 1/2.
fesd::Trajectory passingPlan(double force) {
  const Eigen::VectorXd nodes = fesd::makeTableau(fesd::CollocationFamily::kRadauIIA, 2).c;
  const auto state = [](double t) {
    return Eigen::Vector4d(-1.0 + 2.0 * t, 1.2 - 0.96 * t * (1.0 - t), 0.0, 0.0);
  };
  fesd::Trajectory plan;
  plan.stage_nodes = nodes;
  plan.interval_times = {0.0, 1.0};
  plan.controls = {Eigen::Vector2d(2.0, 0.0)};
  plan.times = {0.0, 1.0};
  plan.states = {state(0.0), state(1.0)};
  fesd::ElementValues element;
  element.interval = 0;
  element.start_time = 0.0;
  element.step = 1.0;
  element.stage_states.resize(4, 2);
  for (int i = 0; i < 2; ++i) element.stage_states.col(i) = state(nodes(i));
  element.stage_multipliers = Eigen::MatrixXd::Constant(1, 2, force);
  element.stage_constraints = Eigen::MatrixXd::Zero(1, 2);
  plan.elements = {element};
  return plan;
}

TEST(PlanVerification, IntervalBoundariesAreTheStatesWhereIntervalsStart) {
  fesd::Trajectory trajectory;
  for (int e = 0; e < 4; ++e) {
    trajectory.states.push_back(Eigen::VectorXd::Constant(1, e));
    fesd::ElementValues element;
    element.interval = e / 2;
    trajectory.elements.push_back(element);
  }
  trajectory.states.push_back(Eigen::VectorXd::Constant(1, 4.0));
  const std::vector<Eigen::VectorXd> boundaries = fesd::intervalBoundaryStates(trajectory);
  ASSERT_EQ(boundaries.size(), 3u);
  EXPECT_EQ(boundaries[0](0), 0.0);
  EXPECT_EQ(boundaries[1](0), 2.0);
  EXPECT_EQ(boundaries[2](0), 4.0);
}

TEST(PlanVerification, APlanCuttingIntoABodyBetweenStagePointsGrazesIt) {
  fesd::SceneTask task = fesd_test::pushingTask();
  task.scene.bodies().resize(2);
  task.bodies.resize(2);
  const std::vector<fesd::ContactPair> pairs{task.scene.allPairs()[0]};
  ASSERT_EQ(task.scene.pairName(pairs[0]), "pusher/puck");
  const std::vector<fesd::Graze> grazes = fesd::planGrazes(task, passingPlan(0.0), pairs, 1e-6);
  ASSERT_EQ(grazes.size(), 1u);
  EXPECT_EQ(grazes[0].interval, 0);
  EXPECT_EQ(grazes[0].element, 0);
  EXPECT_FALSE(grazes[0].touched);
  // The deepest point of |p(t)| - 1 along the parabola (t = 1/2 by symmetry).
  EXPECT_NEAR(grazes[0].fraction, 0.5, 1e-6);
  EXPECT_NEAR(grazes[0].depth, 0.96 - 1.0, 1e-9);
  EXPECT_NEAR(grazes[0].time, 0.5, 1e-6);
  // A plan that holds a force of the pair there is in contact, not grazing; a shallow cut is
  // within the depth.
  EXPECT_TRUE(fesd::planGrazes(task, passingPlan(1.0), pairs, 1e-6).empty());
  EXPECT_TRUE(fesd::planGrazes(task, passingPlan(0.0), pairs, 0.05).empty());
  EXPECT_NE(fesd::describeGrazes(task.scene, grazes).find("pusher/puck at t = 0.5"),
            std::string::npos);
}

TEST(PlanVerification, APushIsVerifiedIntervalByIntervalAndOpenLoop) {
  const fesd::SceneTask task = fesd_test::pushAlongX();
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 3;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  ASSERT_EQ(outcome.status, fesd::SolveStatus::kSuccess) << outcome.message;
  fesd::SimulationOptions fine;
  fine.discretization.num_stages = 3;
  fine.discretization.num_elements = 6;
  const fesd::Verification verification =
      fesd::verifyPlan(task, outcome.trajectory, outcome.decisions, fine, 0.1, 1e-6);
  ASSERT_EQ(verification.status, fesd::SolveStatus::kSuccess) << verification.message;
  ASSERT_EQ(verification.interval_errors.size(), static_cast<size_t>(task.num_intervals));
  EXPECT_EQ(verification.error, *std::max_element(verification.interval_errors.begin(),
                                                  verification.interval_errors.end()));
  EXPECT_LT(verification.error, 1e-6);
  EXPECT_TRUE(std::isfinite(verification.open_loop_error));
  EXPECT_EQ(verification.open_loop.states.size(), 1u + task.num_intervals * 6);
  EXPECT_GE(verification.open_loop_gain, 1.0);  // the puck's own start carries through
  EXPECT_GT(verification.relative_gap, -1e-6);
  EXPECT_TRUE(verification.grazes.empty());
  EXPECT_EQ(verification.modelled_pairs, 1);
}

}  // namespace
