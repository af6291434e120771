// Scenes as tasks (scene/scene_task.cpp): validation messages, goals that cannot be met named
// before any solve, and the reachability pruning of contact pairs. With a robot: speed limits
// and bounds from the URDF or the task, validation messages, reach pruning of pairs and the OCP's
// bounds and costs.
#include <cmath>
#include <map>
#include <memory>
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "support/robot_files.h"
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

// A turning box (boxIntoACorner): its spheres reach min(D sqrt(1 + L^2 / rho^2), D + 2 L), its
// yaw target weighs (w / rho^2) (s - rho target)^2 in s = rho yaw, and what it must not be is
// named.
TEST(SceneTask, ATurningBodysReachCostAndValidation) {
  fesd::SceneTask task = fesd_test::boxIntoACorner();
  ASSERT_EQ(fesd::validateTask(task, fesd::TaskLimits{}), "");
  const double rho = task.scene.turningRadius(1);
  const double travel = task.horizon * std::sqrt(2.0) * 2.0;  // |u_max|: two coordinates at 2
  const double arm = 0.25 * std::sqrt(2.0);
  const std::vector<double> reach = fesd::collisionReach(task);
  ASSERT_EQ(reach.size(), 5u);
  for (int sphere = 1; sphere <= 4; ++sphere) {
    EXPECT_NEAR(reach[sphere],
                std::min(travel * std::sqrt(1.0 + arm * arm / (rho * rho)), travel + 2.0 * arm),
                1e-12);
  }
  const fesd::OcpDefinition ocp = fesd::buildOcp(task, {});
  ASSERT_EQ(ocp.initial_state.size(), 5);
  EXPECT_NEAR(ocp.initial_state(4), rho * 0.3, 1e-15);
  // The Mayer cost at the start: 100 |p - (1, -0.5)|^2 + 100 (0.3 - 0)^2.
  double cost = 0.0;
  ocp.mayer_cost->evaluate(ocp.initial_state.data(), &cost);
  EXPECT_NEAR(cost, 100.0 * (1.0 + 0.25) + 100.0 * 0.09, 1e-9);

  fesd::SceneTask actuated = task;
  actuated.scene.bodies()[1].actuated = true;
  EXPECT_NE(fesd::validateTask(actuated, fesd::TaskLimits{}).find("only passive bodies turn"),
            std::string::npos);
  fesd::SceneTask off_centre = task;
  off_centre.scene.bodies()[1].spheres[0].offset.x() += 0.1;
  EXPECT_NE(fesd::validateTask(off_centre, fesd::TaskLimits{}).find("centre of pressure"),
            std::string::npos);
  fesd::SceneTask yaw_only = task;
  yaw_only.scene.bodies()[1].turns = false;
  EXPECT_NE(fesd::validateTask(yaw_only, fesd::TaskLimits{}).find("does not turn"),
            std::string::npos);
  fesd::SceneTask nan_yaw = task;
  nan_yaw.bodies[1].target_yaw = std::nan("");
  EXPECT_NE(fesd::validateTask(nan_yaw, fesd::TaskLimits{}).find("target yaw"), std::string::npos);
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

namespace {

using fesd::SceneTask;

SceneTask armTask() {
  fesd::Scene discs(2);
  discs.bodies().push_back({"disc", 0.05, Eigen::Vector2d(0.6, 0.3), false});
  discs.obstacles().push_back({"far_post", 0.1, Eigen::Vector2d(10.0, 0.0)});
  discs.obstacles().push_back({"near_post", 0.1, Eigen::Vector2d(0.0, 0.5)});
  SceneTask task = fesd::taskOn(fesd::robotInScene(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")),
      Eigen::Vector3d::Zero(), discs));
  task.bodies[0].target = Eigen::Vector2d(0.6, 0.4);
  task.bodies[0].target_weight = 100.0;
  task.horizon = 1.0;
  return task;
}

TEST(TaskWithARobot, SpeedLimitsAndBoundsFromTheUrdfUnlessOverridden) {
  SceneTask task = armTask();
  EXPECT_EQ(fesd::jointSpeedLimit(task, 1), 1.5);  // the URDF's elbow
  task.joints[1].max_velocity = 0.7;
  EXPECT_EQ(fesd::jointSpeedLimit(task, 1), 0.7);
  EXPECT_EQ(fesd::jointBounds(task, 0), std::make_pair(-2.8, 2.8));
  task.joints[0].has_bounds = true;
  task.joints[0].lower = -0.5;
  task.joints[0].upper = 0.5;
  EXPECT_EQ(fesd::jointBounds(task, 0), std::make_pair(-0.5, 0.5));
}

TEST(TaskWithARobot, ValidationNamesTheProblem) {
  fesd::TaskLimits limits;
  EXPECT_EQ(fesd::validateTask(armTask(), limits), "");
  limits.max_spheres = 5;
  EXPECT_EQ(fesd::validateTask(armTask(), limits), "too many collision spheres: 9 > 5");
  limits = {};
  SceneTask task = armTask();
  task.joints[2].has_bounds = true;
  task.joints[2].lower = 0.1;
  task.joints[2].upper = 1.0;
  EXPECT_EQ(fesd::validateTask(task, limits),
            "joint 'wrist' starts at 0, outside its bounds [0.1, 1]");
  task = armTask();
  task.joints[0].max_velocity = std::nan("");
  EXPECT_EQ(fesd::validateTask(task, limits),
            "joint 'shoulder': the velocity bound must be finite and >= 0");
  fesd::Scene overlapping(2);
  overlapping.bodies().push_back({"disc", 0.05, Eigen::Vector2d(0.9, 0.0), false});
  SceneTask touching = fesd::taskOn(
      fesd::robotInScene(task.scene.robotPointer(), Eigen::Vector3d::Zero(), overlapping));
  EXPECT_EQ(fesd::validateTask(touching, limits), "disc/hand/sphere_1 overlap at the start");
  // A turning body (the corner task's box, far from the arm) in a robot scene: its state is the
  // joints', then its position and s = rho yaw.
  fesd::Scene with_box(2);
  with_box.bodies().push_back(fesd_test::boxIntoACorner().scene.bodies()[1]);
  with_box.bodies().back().position = Eigen::Vector2d(5.0, 5.0);
  const SceneTask turning = fesd::taskOn(
      fesd::robotInScene(task.scene.robotPointer(), Eigen::Vector3d::Zero(), with_box));
  EXPECT_EQ(fesd::validateTask(turning, limits), "");
  EXPECT_EQ(turning.scene.stateSize(), 3 + 3);
  // In a spatial one only on a table: floating it could tilt out of the plane it turns in.
  fesd::Scene spatial(3);
  fesd::SceneBody bar{"bar", 0.05, Eigen::Vector3d(5.0, 5.0, -0.95)};
  bar.spheres = {{"bar/sphere_0", Eigen::Vector3d(0.0, -0.05, 0.0), 0.05},
                 {"bar/sphere_1", Eigen::Vector3d(0.0, 0.05, 0.0), 0.05}};
  fesd::turnAboutPressureCentre(bar, 0.0);
  spatial.bodies().push_back(bar);
  SceneTask turning_in_space =
      fesd::taskOn(fesd::robotInScene(task.scene.robotPointer(), Eigen::Vector3d::Zero(), spatial));
  EXPECT_EQ(fesd::validateTask(turning_in_space, limits),
            "body 'bar' turns in a spatial robot scene: it must rest on a level wall (a table) to "
            "turn about its normal");
  turning_in_space.scene.walls().push_back({"table", Eigen::Vector3d::UnitZ(), -1.0});
  EXPECT_EQ(fesd::validateTask(turning_in_space, limits), "");
  EXPECT_EQ(turning_in_space.scene.supportOf(0), 0);
}

TEST(TaskWithARobot, PairsBeyondReachArePruned) {
  const SceneTask task = armTask();
  bool far_seen = false, near_seen = false;
  for (const fesd::PairDecision& d : fesd::decidePairs(task)) {
    const std::string name = task.scene.pairName(d.pair);
    if (name == "hand/sphere_1/far_post") {
      far_seen = true;
      EXPECT_FALSE(d.modelled) << d.reason;
    }
    if (name == "hand/sphere_1/near_post") {
      near_seen = true;
      EXPECT_TRUE(d.modelled) << d.reason;
    }
    if (name == "disc/far_post") {
      EXPECT_FALSE(d.modelled) << d.reason;
    }
  }
  EXPECT_TRUE(far_seen);
  EXPECT_TRUE(near_seen);
  // The disc gets the reach of what pushes it: T |u_max| with u_max = (1, 1.5, 2).
  const std::vector<double> reach = fesd::collisionReach(task);
  EXPECT_NEAR(reach[0], std::sqrt(1.0 + 2.25 + 4.0), 1e-12);
}

TEST(TaskWithARobot, OnlyAllowedPairsAreModelledAndOnlyThroughThemDoesAPassiveBodyMove) {
  SceneTask task = armTask();
  const std::vector<fesd::ContactPair> all = task.scene.allPairs();
  for (const fesd::ContactPair& pair : all) {
    if (task.scene.pairName(pair) == "hand/sphere_1/near_post") task.allowed_pairs.push_back(pair);
  }
  ASSERT_EQ(task.allowed_pairs.size(), 1u);
  EXPECT_EQ(task.scene.pairSides(task.allowed_pairs[0]),
            std::make_pair(std::string("hand/sphere_1"), std::string("near_post")));
  int modelled = 0;
  for (const fesd::PairDecision& d : fesd::decidePairs(task)) {
    modelled += d.modelled;
    if (!fesd::isAllowed(task, d.pair)) {
      EXPECT_FALSE(d.modelled);
      EXPECT_EQ(d.reason, "not among the allowed pairs");
    }
  }
  EXPECT_EQ(modelled, 1);
  // No allowed pair touches the disc: nothing can push it, so it keeps no reach.
  EXPECT_EQ(fesd::collisionReach(task)[0], 0.0);
}

TEST(TaskWithARobot, AFreeBodyPushedThroughOneSphereMovesAllOfThem) {
  // A bar of two spheres; only its first may meet the hand, only its second the wall beyond.
  fesd::Scene discs(2);
  discs.bodies().push_back({"bar", 0.1, Eigen::Vector2d(0.6, 0.3), false});
  discs.walls().push_back({"side", Eigen::Vector2d(-1.0, 0.0), -1.0});  // x <= 1
  discs.bodies()[0].spheres = {{"bar/sphere_0", Eigen::Vector3d(-0.05, 0.0, 0.0), 0.05},
                               {"bar/sphere_1", Eigen::Vector3d(0.05, 0.0, 0.0), 0.05}};
  SceneTask task = fesd::taskOn(
      fesd::robotInScene(armTask().scene.robotPointer(), Eigen::Vector3d::Zero(), discs));
  task.horizon = 1.0;
  for (const fesd::ContactPair& pair : task.scene.allPairs()) {
    const std::string name = task.scene.pairName(pair);
    if (name == "bar/sphere_0/hand/sphere_1" || name == "bar/sphere_1/side") {
      task.allowed_pairs.push_back(pair);
    }
  }
  ASSERT_EQ(task.allowed_pairs.size(), 2u);
  const std::vector<double> reach = fesd::collisionReach(task);
  EXPECT_GT(reach[0], 0.0);
  EXPECT_EQ(reach[1], reach[0]);
  for (const fesd::PairDecision& d : fesd::decidePairs(task)) {
    if (task.scene.pairName(d.pair) == "bar/sphere_1/side") {
      EXPECT_TRUE(d.modelled) << d.reason;
    }
  }
}

TEST(TaskWithARobot, OcpBoundsAndCosts) {
  SceneTask task = armTask();
  task.joints[2].target = 0.3;
  task.joints[2].target_weight = 10.0;
  const fesd::OcpDefinition ocp = fesd::buildOcp(task, {});
  EXPECT_EQ(ocp.control_upper, Eigen::Vector3d(1.0, 1.5, 2.0));
  EXPECT_EQ(ocp.control_lower, -Eigen::Vector3d(1.0, 1.5, 2.0));
  EXPECT_EQ(ocp.state_lower.head(3), Eigen::Vector3d(-2.8, -2.5, -2.5));
  EXPECT_EQ(ocp.state_upper.head(3), Eigen::Vector3d(2.8, 2.5, 2.5));
  ASSERT_TRUE(ocp.mayer_cost);
  Eigen::VectorXd x = ocp.initial_state;
  double cost = 0.0;
  ocp.mayer_cost->evaluate(x.data(), &cost);
  // 10 (0 - 0.3)^2 + 100 |(0.6, 0.3) - (0.6, 0.4)|^2.
  EXPECT_NEAR(cost, 10.0 * 0.09 + 100.0 * 0.01, 1e-12);
}

}  // namespace

namespace {

TEST(TaskWithARobot, AFreeLinkNeedsAFreeBodyOfTheScene) {
  const fesd::KinematicModelResult built = fesd::buildKinematicModel(R"(<robot name="slider">
    <link name="base"/>
    <link name="arm"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <link name="puck"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <joint name="hinge" type="revolute"><parent link="base"/><child link="arm"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <joint name="free" type="planar"><parent link="base"/><child link="puck"/>
      <origin xyz="1 0 0"/></joint>
  </robot>)");
  ASSERT_EQ(built.error, "");
  const auto robot = std::make_shared<const fesd::KinematicModel>(built.model);
  const fesd::SceneTask bare =
      fesd::taskOn(fesd::robotInScene(robot, Eigen::VectorXd::Zero(1), fesd::Scene(2)));
  EXPECT_EQ(fesd::validateTask(bare, {}),
            "link 'puck' is on a planar or floating joint but no free body of the scene stands "
            "for it (robotForScene makes one)");
  fesd::Scene discs(2);
  discs.bodies().push_back({"puck", 0.1, Eigen::Vector2d(1.0, 0.0), false});
  const fesd::SceneTask with_body =
      fesd::taskOn(fesd::robotInScene(robot, Eigen::VectorXd::Zero(1), discs));
  EXPECT_EQ(fesd::validateTask(with_body, {}), "");
  // The link's body asked to turn: its answer (the robot's joints) has no yaw for it.
  fesd::Scene turning(2);
  fesd::SceneBody puck{"puck", 0.1, Eigen::Vector2d(1.0, 0.0)};
  puck.spheres = {{"puck/sphere_0", Eigen::Vector3d(0.0, -0.1, 0.0), 0.1},
                  {"puck/sphere_1", Eigen::Vector3d(0.0, 0.1, 0.0), 0.1}};
  fesd::turnAboutPressureCentre(puck, 0.0);
  turning.bodies().push_back(puck);
  const fesd::SceneTask with_turning_body =
      fesd::taskOn(fesd::robotInScene(robot, Eigen::VectorXd::Zero(1), turning));
  EXPECT_EQ(fesd::validateTask(with_turning_body, {}),
            "body 'puck' is a free link of the robot's URDF: it translates (add a turning body "
            "instead)");
}

}  // namespace

namespace {

/// fesd_test::puckOnATable with a target 0.2 along x.
fesd::SceneTask tableTask() {
  fesd::SceneTask task = fesd_test::puckOnATable();
  task.bodies[1].target = Eigen::Vector3d(0.2, 0.0, 0.05);
  task.bodies[1].target_weight = 100.0;
  return task;
}

TEST(SceneTaskSupports, ASupportThatCannotHoldItsBodyIsRefusedByName) {
  const fesd::TaskLimits limits;
  EXPECT_EQ(fesd::validateTask(tableTask(), limits), "");
  fesd::SceneTask sandwiched = tableTask();  // a ceiling on the puck too: two level walls
  sandwiched.scene.walls().push_back({"lid", -Eigen::Vector3d::UnitZ(), -0.1});
  EXPECT_EQ(fesd::validateTask(sandwiched, limits),
            "body 'puck' rests on two level walls, 'table' and 'lid': name its support, or let "
            "it float");
  sandwiched.scene.bodies()[1].support = fesd::SupportMode::kWall;
  sandwiched.scene.bodies()[1].support_wall = 1;
  EXPECT_EQ(fesd::validateTask(sandwiched, limits), "");
  fesd::SceneTask tilted = tableTask();
  tilted.scene.walls().push_back({"ramp", Eigen::Vector3d(0.0, 0.6, 0.8), 0.0});
  tilted.scene.bodies()[1].support = fesd::SupportMode::kWall;
  tilted.scene.bodies()[1].support_wall = 1;
  EXPECT_EQ(fesd::validateTask(tilted, limits),
            "body 'puck' cannot slide on 'ramp': a support must be level (normal along z)");
  fesd::SceneTask floating = tableTask();
  floating.scene.bodies()[0].support = fesd::SupportMode::kWall;  // the pusher, 0.02 above
  floating.scene.bodies()[0].support_wall = 0;
  EXPECT_EQ(fesd::validateTask(floating, limits),
            "body 'pusher' does not rest on 'table': its lowest sphere is 0.02 from it");
  fesd::SceneTask nowhere = tableTask();
  nowhere.scene.bodies()[1].support = fesd::SupportMode::kWall;
  nowhere.scene.bodies()[1].support_wall = 7;
  EXPECT_EQ(fesd::validateTask(nowhere, limits),
            "body 'puck': its support is no wall of the scene");
  // A body inside the table is no body resting on it.
  fesd::SceneTask sunk = tableTask();
  sunk.scene.bodies()[1].position.z() = 0.04;
  EXPECT_EQ(fesd::validateTask(sunk, limits), "puck/table overlap at the start");
  // A target off the table's plane cannot be met.
  fesd::SceneTask lifted = tableTask();
  lifted.bodies[1].target.z() = 0.3;
  EXPECT_EQ(fesd::infeasibility(lifted),
            "body 'puck' slides on 'table' at a height of 0.05: its target is off that plane (z = "
            "0.3)");
}

}  // namespace
