// Scenes as tasks: URDF reading, validation, reachability pruning and the moving part.
#include <cmath>
#include <map>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/scene/moving_part.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "fesd_trajopt/scene/urdf_scene.h"

namespace {

/// A pusher at (-3, 0), a puck at the origin (both R = 0.5), a post (R = 0.4) at (0, 3) and a
/// rock (R = 1) at (100, 100) that nothing can reach in T = 2 at speed 2.
fesd::SceneTask pushingTask() {
  fesd::SceneTask task;
  task.scene.bodies() = {{"pusher", 0.5, Eigen::Vector2d(-3.0, 0.0), true},
                         {"puck", 0.5, Eigen::Vector2d(0.0, 0.0), false},
                         {"rock", 1.0, Eigen::Vector2d(100.0, 100.0), false}};
  task.scene.obstacles() = {{"post", 0.4, Eigen::Vector2d(0.0, 3.0)}};
  task.bodies.resize(3);
  task.bodies[0].max_speed = 2.0;
  task.horizon = 2.0;
  task.num_intervals = 4;
  return task;
}

TEST(UrdfScene, SpheresAndUprightCylindersBecomeBodiesAndFixedLinksObstacles) {
  const std::string urdf = R"(<robot name="r"><link name="world"/>
    <link name="a"><collision><geometry><sphere radius="0.5"/></geometry></collision></link>
    <joint name="ja" type="floating"><parent link="world"/><child link="a"/>
      <origin xyz="1 2 3"/></joint>
    <link name="b"><collision><origin xyz="0.5 0 0"/>
      <geometry><cylinder radius="0.7" length="0.1"/></geometry></collision></link>
    <joint name="jb" type="planar"><parent link="world"/><child link="b"/>
      <origin xyz="-1 0 0"/></joint>
    <link name="post"><collision><geometry><sphere radius="0.3"/></geometry></collision></link>
    <joint name="jp" type="fixed"><parent link="world"/><child link="post"/>
      <origin xyz="0 4 0"/></joint>
    <link name="tilted"><collision><origin rpy="1.5707963 0 0"/>
      <geometry><cylinder radius="1" length="1"/></geometry></collision></link>
    <joint name="jt" type="floating"><parent link="world"/><child link="tilted"/></joint>
  </robot>)";
  const fesd::UrdfScene planar = fesd::sceneFromUrdf(urdf, true);
  ASSERT_EQ(planar.error, "");
  ASSERT_EQ(planar.scene.bodies().size(), 2u);
  EXPECT_EQ(planar.scene.bodies()[0].name, "a");
  EXPECT_EQ(planar.scene.bodies()[0].radius, 0.5);
  EXPECT_TRUE(planar.scene.bodies()[0].position.isApprox(Eigen::Vector2d(1.0, 2.0)));
  EXPECT_EQ(planar.scene.bodies()[1].radius, 0.7);
  EXPECT_TRUE(planar.scene.bodies()[1].position.isApprox(Eigen::Vector2d(-0.5, 0.0)));
  ASSERT_EQ(planar.scene.obstacles().size(), 1u);
  EXPECT_TRUE(planar.scene.obstacles()[0].position.isApprox(Eigen::Vector2d(0.0, 4.0)));
  EXPECT_EQ(planar.ignored_links, std::vector<std::string>{"tilted"});  // the root is the frame

  const fesd::UrdfScene spatial = fesd::sceneFromUrdf(urdf, false);
  ASSERT_EQ(spatial.error, "");
  ASSERT_EQ(spatial.scene.bodies().size(), 1u);  // cylinders are not spheres in space
  EXPECT_TRUE(spatial.scene.bodies()[0].position.isApprox(Eigen::Vector3d(1.0, 2.0, 3.0)));

  EXPECT_NE(fesd::sceneFromUrdf("<robot name='x'><link name=", true).error.find("malformed"),
            std::string::npos);
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
