// The moving part of a task (scene/moving_part.cpp): a passive body out of reach is left out of
// the model and keeps its place in the full-scene trajectory of a simulated push.
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/scene/moving_part.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "support/scene_tasks.h"

namespace {

/// The pushing task with a post (fesd_test::pushingTaskWithPost).
fesd::SceneTask pushingTask() {
  return fesd_test::pushingTaskWithPost();
}

TEST(MovingPart, APassiveBodyOutOfReachIsLeftOutAndKeepsItsPlace) {
  const fesd::SceneTask task = pushingTask();
  const std::vector<fesd::PairDecision> decisions = fesd::decidePairs(task);
  const fesd::MovingPart part = fesd::movingPart(task, decisions);
  EXPECT_EQ(part.bodies, (std::vector<int>{0, 1}));
  EXPECT_EQ(part.task.scene.stateSize(), 4);
  ASSERT_EQ(part.modelled.size(), 3u);
  for (const fesd::ContactPair& pair : part.modelled) EXPECT_LT(pair.body, 2);

  // Under u = (2, 0) the pusher touches the puck at t = 1; in contact the projection shares the
  // velocity: both move at 1 m/s, so p_pusher(2) = (0, 0) and p_puck(2) = (1, 0).
  fesd::SimulationOptions options;
  options.discretization.num_elements = 2;
  fesd::FesdIntegrator integrator(part.task.scene.model(part.modelled), options);
  const fesd::SimulationResult result = integrator.simulate(
      part.task.scene.initialState(), task.horizon, task.num_intervals, {Eigen::Vector2d(2, 0)});
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  const fesd::Trajectory full = fesd::fullSceneTrajectory(task, part, result.trajectory);
  Eigen::VectorXd expected(6);
  expected << 0.0, 0.0, 1.0, 0.0, 100.0, 100.0;
  EXPECT_LT((full.finalState() - expected).norm(), 1e-9);
  for (const fesd::ElementValues& element : full.elements) {
    ASSERT_EQ(element.stage_states.rows(), 6);
    EXPECT_TRUE(
        (element.stage_states.bottomRows(2).colwise() - Eigen::Vector2d(100, 100)).isZero(0.0));
  }
  ASSERT_FALSE(full.switches.empty());
  EXPECT_NEAR(full.switches.front().time, 1.0, 1e-9);
  EXPECT_EQ(part.task.scene.pairName(part.modelled[full.switches.front().constraint]),
            task.scene.pairName(decisions[0].pair));
}

}  // namespace
