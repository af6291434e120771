// Contact chains. A push that propagates through three discs in a line against
// its analytic solution, and a twelve-disc scene in which pruning leaves only the chain.
#include <map>

#include <gtest/gtest.h>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/scene/moving_part.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace {

/// A pusher at x = -3 and three passive discs at x = 0, 2, 4 (all R = 0.5, gaps 2, 1, 1).
/// With `rocks`, eight more passive discs in a row at y = 50 that nothing can reach.
fesd::SceneTask chainTask(bool rocks) {
  fesd::SceneTask task;
  task.scene.bodies() = {{"pusher", 0.5, Eigen::Vector2d(-3.0, 0.0), true},
                         {"first", 0.5, Eigen::Vector2d(0.0, 0.0), false},
                         {"second", 0.5, Eigen::Vector2d(2.0, 0.0), false},
                         {"third", 0.5, Eigen::Vector2d(4.0, 0.0), false}};
  for (int r = 0; rocks && r < 8; ++r) {
    task.scene.bodies().push_back(
        {"rock" + std::to_string(r), 0.5, Eigen::Vector2d(3.0 * r - 10.0, 50.0), false});
  }
  task.bodies.resize(task.scene.bodies().size());
  task.bodies[0].max_speed = 2.0;
  task.horizon = 4.0;
  task.num_intervals = 5;
  return task;
}

/// Under u = (2, 0) the velocity is the projection of (2, 0, 0, 0) (x components) onto
/// v_pusher <= v_first <= v_second <= v_third once in contact: the discs in contact share it.
/// The pusher meets the first disc at t = 1 (2 m at 2 m/s), both meet the second at t = 2
/// (1 m at 1 m/s), all three the third at t = 3.5 (1 m at 2/3 m/s); then 0.5 m/s each.
TEST(ContactChains, APushPropagatesThroughThreeDiscsAsTheProjectionPredicts) {
  const fesd::SceneTask task = chainTask(false);
  const std::vector<fesd::PairDecision> decisions = fesd::decidePairs(task);
  std::vector<fesd::ContactPair> pairs;
  for (const fesd::PairDecision& d : decisions) {
    EXPECT_TRUE(d.modelled) << task.scene.pairName(d.pair);  // D = 11.3 covers the chain
    pairs.push_back(d.pair);
  }
  ASSERT_EQ(pairs.size(), 6u);
  fesd::SimulationOptions options;
  options.discretization.num_elements = 2;
  fesd::FesdIntegrator integrator(task.scene.model(pairs), options);
  // Ten steps of 0.4 s: the switches at 1 and 3.5 s fall inside steps.
  const fesd::SimulationResult result =
      integrator.simulate(task.scene.initialState(), task.horizon, 10, {Eigen::Vector2d(2, 0)});
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  EXPECT_LE(result.totals.complementarity_residual, 1e-9);
  EXPECT_TRUE(result.trajectory.switchesResolved()) << result.message;
  Eigen::VectorXd expected(8);
  expected << 1.25, 0.0, 2.25, 0.0, 3.25, 0.0, 4.25, 0.0;
  EXPECT_LT((result.trajectory.finalState() - expected).norm(), 1e-8)
      << result.trajectory.finalState().transpose();
  for (const Eigen::VectorXd& x : result.trajectory.states) ASSERT_TRUE(x.allFinite());

  std::vector<std::pair<std::string, double>> contacts;
  for (const fesd::SwitchEvent& event : result.trajectory.switches) {
    ASSERT_EQ(event.kind, fesd::SwitchEvent::Kind::kContact);  // nothing separates
    contacts.push_back({task.scene.pairName(pairs[event.constraint]), event.time});
  }
  ASSERT_EQ(contacts.size(), 3u);
  EXPECT_EQ(contacts[0].first, "pusher/first");
  EXPECT_EQ(contacts[1].first, "first/second");
  EXPECT_EQ(contacts[2].first, "second/third");
  EXPECT_NEAR(contacts[0].second, 1.0, 1e-8);
  EXPECT_NEAR(contacts[1].second, 2.0, 1e-8);
  EXPECT_NEAR(contacts[2].second, 3.5, 1e-8);

  // Repeated: bitwise the same.
  const fesd::SimulationResult again =
      integrator.simulate(task.scene.initialState(), task.horizon, 10, {Eigen::Vector2d(2, 0)});
  EXPECT_EQ(again.trajectory.states, result.trajectory.states);

  // Steps of 0.8 s (1.6 m of travel, more than a disc's diameter) on two elements each: the
  // implicit steps let the pusher pass through the first disc, the chain ends far from the
  // analytic state. That must never be a full-accuracy success: the solution reports the
  // passage.
  fesd::SimulationOptions two_elements = options;
  two_elements.refine_elements = false;
  const fesd::SimulationResult passage =
      fesd::FesdIntegrator(task.scene.model(pairs), two_elements)
          .simulate(task.scene.initialState(), task.horizon, 5, {Eigen::Vector2d(2, 0)});
  EXPECT_GT((passage.trajectory.finalState() - expected).norm(), 1.0);
  EXPECT_FALSE(passage.status == fesd::SolveStatus::kSuccess &&
               passage.trajectory.switchesResolved())
      << passage.message;
  // By default a step whose solution is not exact or stretches an element is solved again on
  // twice the elements, which resolves the chain.
  const fesd::SimulationResult coarse =
      integrator.simulate(task.scene.initialState(), task.horizon, 5, {Eigen::Vector2d(2, 0)});
  ASSERT_EQ(coarse.status, fesd::SolveStatus::kSuccess) << coarse.message;
  EXPECT_GE(coarse.refined_parts, 1);
  EXPECT_TRUE(coarse.trajectory.switchesResolved()) << coarse.message;
  EXPECT_LT((coarse.trajectory.finalState() - expected).norm(), 1e-8);
}

TEST(ContactChains, InATwelveDiscSceneOnlyTheChainIsModelledAndMoves) {
  const fesd::SceneTask task = chainTask(true);
  const std::vector<fesd::PairDecision> decisions = fesd::decidePairs(task);
  ASSERT_EQ(decisions.size(), 66u);  // 12 choose 2
  std::map<std::string, int> reasons;
  int modelled = 0;
  for (const fesd::PairDecision& d : decisions) {
    modelled += d.modelled;
    if (!d.modelled) ++reasons[d.reason.substr(0, 12)];
  }
  // The six chain pairs; the 28 rock pairs cannot move, the 32 chain-rock pairs stay apart
  // (reach boxes within y = +-11.3 of the chain, rocks at y = 50).
  EXPECT_EQ(modelled, 6);
  EXPECT_EQ(reasons["neither side"], 28);
  EXPECT_EQ(reasons["cannot touch"], 32);
  const fesd::MovingPart part = fesd::movingPart(task, decisions);
  ASSERT_EQ(part.bodies, (std::vector<int>{0, 1, 2, 3}));

  fesd::SimulationOptions options;
  options.discretization.num_elements = 2;
  fesd::FesdIntegrator integrator(part.task.scene.model(part.modelled), options);
  const fesd::SimulationResult result = integrator.simulate(
      part.task.scene.initialState(), task.horizon, 10, {Eigen::Vector2d(2, 0)});
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  const fesd::Trajectory full = fesd::fullSceneTrajectory(task, part, result.trajectory);
  Eigen::VectorXd chain_end(8);
  chain_end << 1.25, 0.0, 2.25, 0.0, 3.25, 0.0, 4.25, 0.0;
  EXPECT_LT((full.finalState().head<8>() - chain_end).norm(), 1e-8);
  for (const Eigen::VectorXd& x : full.states) {  // the rocks never move
    for (int b = 4; b < 12; ++b) ASSERT_EQ(x.segment<2>(2 * b), task.scene.bodies()[b].position);
  }
  // The same problem as the chain alone: bitwise the same result.
  const fesd::SceneTask alone = chainTask(false);
  fesd::FesdIntegrator chain_integrator(alone.scene.model(alone.scene.allPairs()), options);
  EXPECT_EQ(chain_integrator
                .simulate(alone.scene.initialState(), task.horizon, 10, {Eigen::Vector2d(2, 0)})
                .trajectory.states,
            result.trajectory.states);
}

}  // namespace
