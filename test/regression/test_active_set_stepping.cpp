// The integrator with active-set steps (the default) against the pure homotopy on the same
// grids: the same trajectories, and how many parts each path took.
#include <cmath>
#include <cstdio>
#include <limits>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/circle_example.h"
#include "fesd_trajopt/examples/filippov_examples.h"
#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/examples/push_scenes.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/moving_part.h"

namespace {

struct BothPaths {
  fesd::SimulationResult active_set, homotopy;
};

BothPaths simulateBoth(std::shared_ptr<const fesd::DynamicsModel> model, const Eigen::VectorXd& x0,
                       double horizon, int steps, fesd::SimulationOptions options,
                       const std::vector<Eigen::VectorXd>& controls = {}) {
  BothPaths runs;
  options.active_set_steps = true;
  runs.active_set = fesd::FesdIntegrator(model, options).simulate(x0, horizon, steps, controls);
  options.active_set_steps = false;
  runs.homotopy = fesd::FesdIntegrator(model, options).simulate(x0, horizon, steps, controls);
  return runs;
}

/// Same element times, boundary states and switches, to `tolerance` (the polishing solve's Ipopt
/// tolerance, 1e-10, leaves the homotopy's solution ~1e-9 from the exact one Newton finds). Where
/// one path split or refined a step the other solved whole, the grids differ: then the end
/// states agree, and the switches to 1e-6.
void expectSameTrajectories(const BothPaths& runs, double tolerance) {
  ASSERT_EQ(runs.active_set.status, fesd::SolveStatus::kSuccess) << runs.active_set.message;
  ASSERT_EQ(runs.homotopy.status, fesd::SolveStatus::kSuccess) << runs.homotopy.message;
  const fesd::Trajectory& a = runs.active_set.trajectory;
  const fesd::Trajectory& b = runs.homotopy.trajectory;
  std::printf("grids %zu / %zu elements, end states %.2e apart\n", a.elements.size(),
              b.elements.size(), (a.finalState() - b.finalState()).norm());
  EXPECT_LT((a.finalState() - b.finalState()).lpNorm<Eigen::Infinity>(), tolerance);
  const bool same_grid = a.times.size() == b.times.size();
  for (size_t i = 0; same_grid && i < a.times.size(); ++i) {
    EXPECT_NEAR(a.times[i], b.times[i], tolerance) << "boundary " << i;
    EXPECT_LT((a.states[i] - b.states[i]).lpNorm<Eigen::Infinity>(), tolerance) << "state " << i;
  }
  ASSERT_EQ(a.switches.size(), b.switches.size());
  for (size_t i = 0; i < a.switches.size(); ++i) {
    EXPECT_EQ(a.switches[i].kind, b.switches[i].kind);
    // On other grids the switches are placed to the discretisation's accuracy, not exactly.
    EXPECT_NEAR(a.switches[i].time, b.switches[i].time, same_grid ? tolerance : 1e-6);
  }
  EXPECT_EQ(runs.homotopy.predicted_parts + runs.homotopy.located_parts, 0);
}

TEST(ActiveSetStepping, ExampleOneMatchesTheHomotopyWithoutAnIpoptIteration) {
  namespace example = fesd::circle_example;
  for (const int stages : {2, 3, 4}) {
    for (const int steps : {5, 10, 20}) {
      fesd::SimulationOptions options;
      options.discretization.num_stages = stages;
      options.refine_elements = false;  // the paper's grid: 2 elements per step
      const BothPaths runs = simulateBoth(example::model(), example::initialState(),
                                          example::horizon(), steps, options);
      SCOPED_TRACE("n_s = " + std::to_string(stages) + ", steps = " + std::to_string(steps));
      expectSameTrajectories(runs, 1e-8);
      EXPECT_EQ(runs.active_set.totals.iterations, 0);
      EXPECT_EQ(runs.active_set.located_parts, 2);  // the contact's step and the release's
      EXPECT_EQ(runs.active_set.predicted_parts, steps - 2);
      EXPECT_EQ(runs.active_set.homotopy_parts, 0);
    }
  }
}

TEST(ActiveSetStepping, AReferenceRunPredictsItsModesAndAWrongOneCostsNoHomotopy) {
  // simulate() with a reference, as a plan's open-loop run is verified: a right reference
  // (the run itself) and a wrong one (in contact throughout, which the start contradicts) give
  // the run without one; the wrong one's parts fall back to the modes the run's history predicts.
  namespace example = fesd::circle_example;
  fesd::SimulationOptions options;
  options.discretization.num_stages = 3;
  options.refine_elements = false;
  const int steps = 10;
  fesd::FesdIntegrator integrator(example::model(), options);
  const fesd::SimulationResult plain =
      integrator.simulate(example::initialState(), example::horizon(), steps);
  ASSERT_EQ(plain.status, fesd::SolveStatus::kSuccess) << plain.message;
  fesd::Trajectory reference = plain.trajectory;
  for (const bool right : {true, false}) {
    SCOPED_TRACE(right ? "the run as its reference" : "in contact throughout");
    if (!right) {
      for (fesd::ElementValues& element : reference.elements) element.stage_multipliers.setOnes();
    }
    const fesd::SimulationResult run =
        integrator.simulate(example::initialState(), example::horizon(), steps, {}, &reference);
    ASSERT_EQ(run.status, fesd::SolveStatus::kSuccess) << run.message;
    EXPECT_EQ(run.totals.iterations, 0);
    EXPECT_EQ(run.homotopy_parts, 0);
    ASSERT_EQ(run.trajectory.times.size(), plain.trajectory.times.size());
    for (size_t i = 0; i < run.trajectory.times.size(); ++i) {
      EXPECT_NEAR(run.trajectory.times[i], plain.trajectory.times[i], 1e-12);
      EXPECT_LT((run.trajectory.states[i] - plain.trajectory.states[i]).norm(), 1e-12);
    }
    ASSERT_EQ(run.trajectory.switches.size(), 2u);
    if (right) {
      EXPECT_GT(run.predicted_parts, plain.predicted_parts);  // the contact's step
    }
  }
}

TEST(ActiveSetStepping, AStepSplitBeforeItsHomotopySkipsTheWholeStepsHomotopy) {
  // One step of Example 1 from t = 1 to 3.5 on 2 elements holds the contact (1.309) and the
  // release (3.041): one free boundary for two switches, no active set solves it whole. Split
  // first (a verification's setting), parts that still fail are split again and every part is
  // solved by its active sets; the step's homotopy first fails and costs its iterations.
  namespace example = fesd::circle_example;
  fesd::SimulationOptions options;
  options.discretization.num_stages = 3;
  options.discretization.num_elements = 2;
  options.refine_elements = false;
  const Eigen::VectorXd x0 = example::exactState(1.0);
  const Eigen::VectorXd exact = example::exactState(3.5);
  options.split_before_homotopy = true;
  const fesd::SimulationResult split =
      fesd::FesdIntegrator(example::model(), options).simulate(x0, 2.5, 1);
  options.split_before_homotopy = false;
  const fesd::SimulationResult homotopy_first =
      fesd::FesdIntegrator(example::model(), options).simulate(x0, 2.5, 1);
  ASSERT_EQ(split.status, fesd::SolveStatus::kSuccess) << split.message;
  ASSERT_EQ(homotopy_first.status, fesd::SolveStatus::kSuccess) << homotopy_first.message;
  std::printf("Ipopt iterations: split first %d (%d parts by homotopy), homotopy first %d\n",
              split.totals.iterations, split.homotopy_parts, homotopy_first.totals.iterations);
  EXPECT_EQ(split.split_steps, 1);
  EXPECT_EQ(split.homotopy_parts, 0);
  EXPECT_EQ(homotopy_first.split_steps, 1);
  EXPECT_LT(split.totals.iterations, homotopy_first.totals.iterations);
  ASSERT_EQ(split.trajectory.switches.size(), 2u);
  EXPECT_NEAR(split.trajectory.switches[0].time, example::contactTime() - 1.0, 1e-6);
  EXPECT_NEAR(split.trajectory.switches[1].time, example::releaseTime() - 1.0, 1e-3);
  EXPECT_LT((split.trajectory.finalState() - exact).norm(), 1e-3);
}

TEST(ActiveSetStepping, RandomPushScenesMatchTheHomotopy) {
  namespace ps = fesd::push_scenes;
  for (const unsigned seed : {0u, 7u, 12u, 13u}) {
    const ps::PushScene scene = ps::randomPushScene(seed);
    for (const int steps : {5, 8, 12}) {
      fesd::SimulationOptions options;
      options.discretization.num_stages = 3;
      const BothPaths runs = simulateBoth(scene.model(), scene.initialState(), scene.horizon, steps,
                                          options, {scene.velocity});
      SCOPED_TRACE(scene.describe() + ", steps = " + std::to_string(steps));
      expectSameTrajectories(runs, 1e-8);
      EXPECT_GT(runs.active_set.predicted_parts + runs.active_set.located_parts, 0);
      RecordProperty(
          "homotopy_parts_seed" + std::to_string(seed) + "_steps" + std::to_string(steps),
          runs.active_set.homotopy_parts);
    }
  }
}

TEST(ActiveSetStepping, FilippovSpiralMatchesTheHomotopyAndPredictsStepsWithoutCrossing) {
  namespace spiral = fesd::spiral_example;
  for (const auto family :
       {fesd::CollocationFamily::kRadauIIA, fesd::CollocationFamily::kGaussLegendre}) {
    fesd::SimulationOptions options;
    options.discretization.family = family;
    options.discretization.num_stages = 2;
    const BothPaths runs =
        simulateBoth(spiral::model(), spiral::initialState(), spiral::horizon(), 16, options);
    expectSameTrajectories(runs, 1e-8);
    EXPECT_GE(runs.active_set.predicted_parts, 14);  // every step but the crossing's
    EXPECT_LT(runs.active_set.totals.iterations, runs.homotopy.totals.iterations / 4);
  }
}

TEST(ActiveSetStepping, TheShowcasePlanIsReSimulatedWithoutTheHomotopy) {
  // The verification of the default scene's plan: both pushers touch the object at one element
  // boundary (two equations for one free step), and both let go where the control changes at
  // t = 3.5 (a force carried into a step that releases at its start). Both steps took the
  // homotopy, 56 Ipopt iterations; now they are located by Newton, to the homotopy's switches.
  const fesd::SceneTask task = fesd::manipulation_example::task(40);
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 3;
  options.ocp.discretization.num_stages = 2;
  const fesd::SceneOutcome plan = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  ASSERT_EQ(plan.status, fesd::SolveStatus::kSuccess) << plan.message;
  fesd::DiscretizationOptions verification;
  verification.num_stages = 3;
  verification.num_elements = 6;
  const fesd::SimulationOptions fine =
      fesd::verificationOptions(verification, options.ocp, std::numeric_limits<double>::infinity());
  const fesd::MovingPart part = fesd::movingPart(task, plan.decisions);
  const fesd::OcpDefinition ocp = fesd::buildOcp(part.task, part.modelled);
  const BothPaths runs = simulateBoth(ocp.model, ocp.initial_state, ocp.horizon, ocp.num_intervals,
                                      fine, plan.trajectory.controls);
  ASSERT_EQ(runs.active_set.status, fesd::SolveStatus::kSuccess) << runs.active_set.message;
  ASSERT_EQ(runs.homotopy.status, fesd::SolveStatus::kSuccess) << runs.homotopy.message;
  EXPECT_EQ(runs.active_set.totals.iterations, 0);
  EXPECT_EQ(runs.active_set.homotopy_parts, 0);
  EXPECT_EQ(runs.active_set.located_parts, 2);
  // The homotopy leaves the steps around the release's boundary 3.5e-8 apart (the freedom the
  // equal-step ties take away), which moves no state at the step's end: the released bodies
  // move in straight lines.
  const fesd::Trajectory& a = runs.active_set.trajectory;
  const fesd::Trajectory& b = runs.homotopy.trajectory;
  EXPECT_LT((a.finalState() - b.finalState()).lpNorm<Eigen::Infinity>(), 1e-8);
  ASSERT_EQ(a.switches.size(), 4u);
  ASSERT_EQ(b.switches.size(), 4u);
  for (size_t i = 0; i < a.switches.size(); ++i) {
    EXPECT_EQ(a.switches[i].kind, b.switches[i].kind);
    EXPECT_NEAR(a.switches[i].time, b.switches[i].time, 1e-8);
  }
  EXPECT_NEAR(a.switches.front().time, 1.3321, 1e-4);
  EXPECT_NEAR(a.switches.back().time, 3.5, 1e-12);
}

}  // namespace
