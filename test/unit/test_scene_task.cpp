// Scenes as tasks (scene/scene_task.cpp): validation messages, goals that cannot be met named
// before any solve, and the reachability pruning of contact pairs.
#include <cmath>
#include <map>
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "support/scene_tasks.h"

namespace {

using fesd_test::slowPushingTask;

/// The pushing task with a post (fesd_test::pushingTaskWithPost).
fesd::SceneTask pushingTask() {
  return fesd_test::pushingTaskWithPost();
}

TEST(SceneTask, ValidationNamesTheProblem) {
  const fesd::TaskLimits limits;
  EXPECT_EQ(fesd::validateTask(pushingTask(), limits), "");
  auto problem = [&](auto change) {
    fesd::SceneTask task = pushingTask();
    change(task);
    return fesd::validateTask(task, limits);
  };
  EXPECT_NE(problem([](auto& t) { t.scene.bodies()[1].radius = -1.0; }).find("radius"),
            std::string::npos);
  EXPECT_NE(problem([](auto& t) { t.scene.bodies()[1].position(0) = NAN; }).find("not finite"),
            std::string::npos);
  EXPECT_NE(problem([](auto& t) { t.scene.bodies()[1].position(0) = -2.5; }).find("overlap"),
            std::string::npos);
  EXPECT_NE(problem([](auto& t) { t.scene.bodies()[0].actuated = false; }).find("actuated"),
            std::string::npos);
  EXPECT_NE(problem([](auto& t) { t.horizon = 0.0; }).find("horizon"), std::string::npos);
  EXPECT_NE(problem([](auto& t) { t.num_intervals = 100000; }).find("intervals"),
            std::string::npos);
  EXPECT_NE(problem([](auto& t) {
              t.bodies[0].workspace_upper = Eigen::Vector2d(-4.0, 9.0);
            }).find("outside its workspace"),
            std::string::npos);
}

TEST(SceneTask, PruningKeepsExactlyThePairsThatCanTouch) {
  const fesd::SceneTask task = pushingTask();
  std::vector<std::string> modelled, pruned;
  for (const fesd::PairDecision& d : fesd::decidePairs(task)) {
    (d.modelled ? modelled : pruned).push_back(task.scene.pairName(d.pair));
  }
  // Reach D = T |u_max| = 2 * 2 * sqrt(2): the pusher can reach the puck and the post; the
  // passive puck can be pushed as far, so it reaches the post too. The rock is out of reach.
  EXPECT_EQ(modelled.size(), 3u);
  EXPECT_EQ(pruned.size(), 3u);
  for (const std::string& name : pruned) EXPECT_NE(name.find("rock"), std::string::npos) << name;

  fesd::SceneTask slow = task;
  slow.bodies[0].max_speed = 0.3;  // D = 0.85 < the pusher's gap 2 to the puck
  for (const fesd::PairDecision& d : fesd::decidePairs(slow)) EXPECT_FALSE(d.modelled);

  // The paper's showcase: the workspace bounds keep the actuators apart.
  const fesd::SceneTask showcase = fesd::manipulation_example::task(40);
  int showcase_modelled = 0;
  for (const fesd::PairDecision& d : fesd::decidePairs(showcase)) {
    showcase_modelled += d.modelled;
    if (d.pair.kind == fesd::ContactPair::Kind::kBody && d.pair.body == 0 && d.pair.other == 1) {
      EXPECT_FALSE(d.modelled);
    }
  }
  EXPECT_EQ(showcase_modelled, 2);
}

TEST(SceneTask, PassiveBodiesMoveOnlyWhenSomethingThatMovesCanReachThem) {
  fesd::SceneTask task = pushingTask();
  // Two more rocks beside the first, out of everyone's reach: no pair among them is modelled.
  task.scene.bodies().push_back({"rock_b", 1.0, Eigen::Vector2d(103.0, 100.0), false});
  task.scene.bodies().push_back({"rock_c", 1.0, Eigen::Vector2d(106.0, 100.0), false});
  // A chain, D = 5.66: the pusher's box ends at x = 2.66, short of the marble (4, 0); the puck
  // can reach the marble, which then can reach the pebble (8, 0).
  task.scene.bodies().push_back({"marble", 0.5, Eigen::Vector2d(4.0, 0.0), false});
  task.scene.bodies().push_back({"pebble", 0.5, Eigen::Vector2d(8.0, 0.0), false});
  task.bodies.resize(task.scene.bodies().size());
  std::map<std::string, const fesd::PairDecision*> by_name;
  const std::vector<fesd::PairDecision> decisions = fesd::decidePairs(task);
  for (const fesd::PairDecision& d : decisions) by_name[task.scene.pairName(d.pair)] = &d;
  auto decision = [&](const std::string& name) {
    EXPECT_TRUE(by_name.count(name)) << name;
    return by_name.count(name) ? *by_name.at(name) : fesd::PairDecision{};
  };
  EXPECT_FALSE(decision("rock/rock_b").modelled);
  EXPECT_NE(decision("rock/rock_b").reason.find("nothing can push"), std::string::npos);
  EXPECT_FALSE(decision("rock_b/rock_c").modelled);
  EXPECT_TRUE(decision("puck/marble").modelled);
  EXPECT_TRUE(decision("marble/pebble").modelled);
  EXPECT_TRUE(decision("pusher/pebble").modelled);  // both boxes have reach D: x 2.66 > 2.34
  EXPECT_FALSE(decision("pebble/post").modelled);   // x gap 2.34 - 0.9 > 0

  // Without the puck-marble pair the chain breaks: the pusher misses the marble by 0.34, so
  // marble and pebble cannot move.
  for (const fesd::PairDecision& d : decisions) {
    if (task.scene.pairName(d.pair) != "puck/marble") task.allowed_pairs.push_back(d.pair);
  }
  for (const fesd::PairDecision& d : fesd::decidePairs(task)) {
    if (task.scene.pairName(d.pair) == "marble/pebble") {
      EXPECT_FALSE(d.modelled);
    }
  }
}

std::string infeasibility(void (*change)(fesd::SceneTask&)) {
  fesd::SceneTask task = slowPushingTask();
  change(task);
  EXPECT_EQ(fesd::validateTask(task, fesd::TaskLimits{}), "");  // well-formed, just impossible
  return fesd::infeasibility(task);
}

TEST(InfeasibleTasks, TargetsOutsideTheWorkspaceOrOutOfReachAreNamed) {
  EXPECT_EQ(infeasibility([](fesd::SceneTask& t) {
              t.bodies[1].target = Eigen::Vector2d(1.5, 0.0);
              t.bodies[1].target_weight = 1.0;
            }),
            "");
  EXPECT_EQ(infeasibility([](fesd::SceneTask& t) {
              t.bodies[1].target = Eigen::Vector2d(1.5, 0.0);
              t.bodies[1].target_weight = 1.0;
              t.bodies[1].workspace_upper = Eigen::Vector2d(1.0, 5.0);
            }),
            "body 'puck' has its target outside its workspace bounds");
  // The pusher's box ends at x = -3 + 2.83 = -0.17: it misses (10, 0) by 10.2.
  EXPECT_EQ(infeasibility([](fesd::SceneTask& t) {
              t.bodies[0].target = Eigen::Vector2d(10.0, 0.0);
              t.bodies[0].target_weight = 1.0;
            }),
            "body 'pusher' cannot reach its target within the horizon: it stays at least 10.2 "
            "away");
  EXPECT_EQ(infeasibility([](fesd::SceneTask& t) {
              t.bodies[2].target = Eigen::Vector2d(51.0, 0.0);
              t.bodies[2].target_weight = 1.0;
            }),
            "body 'rock' cannot reach its target within the horizon: it stays at least 1 away "
            "(nothing that moves can push it)");
  // A target without weight is no goal.
  EXPECT_EQ(infeasibility([](fesd::SceneTask& t) { t.bodies[0].target = Eigen::Vector2d(9, 9); }),
            "");
}

TEST(InfeasibleTasks, ContradictoryBoundsAreRefusedByValidation) {
  fesd::SceneTask task = slowPushingTask();
  task.bodies[1].workspace_lower = Eigen::Vector2d(-1.0, -1.0);
  task.bodies[1].workspace_upper = Eigen::Vector2d(1.0, -2.0);
  EXPECT_EQ(fesd::validateTask(task, fesd::TaskLimits{}),
            "body 'puck': the workspace bounds are contradictory (lower > upper)");
}

}  // namespace
