// Robot tasks (scene/robot_task.cpp): speed limits and bounds from the URDF or the task,
// validation messages, reach pruning of pairs and the OCP's bounds and costs.
#include <memory>

#include <gtest/gtest.h>

#include "fesd_trajopt/scene/robot_task.h"
#include "support/robot_files.h"

namespace {

using fesd::RobotTask;

RobotTask armTask() {
  fesd::DiscScene discs(2);
  discs.bodies().push_back({"disc", 0.05, Eigen::Vector2d(0.6, 0.3), false});
  discs.obstacles().push_back({"far_post", 0.1, Eigen::Vector2d(10.0, 0.0)});
  discs.obstacles().push_back({"near_post", 0.1, Eigen::Vector2d(0.0, 0.5)});
  RobotTask task(fesd::RobotScene(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")),
      Eigen::Vector3d::Zero(), discs));
  task.bodies[0].target = Eigen::Vector2d(0.6, 0.4);
  task.bodies[0].target_weight = 100.0;
  task.horizon = 1.0;
  return task;
}

TEST(RobotTask, SpeedLimitsAndBoundsFromTheUrdfUnlessOverridden) {
  RobotTask task = armTask();
  EXPECT_EQ(fesd::jointSpeedLimit(task, 1), 1.5);  // the URDF's elbow
  task.joints[1].max_velocity = 0.7;
  EXPECT_EQ(fesd::jointSpeedLimit(task, 1), 0.7);
  EXPECT_EQ(fesd::jointBounds(task, 0), std::make_pair(-2.8, 2.8));
  task.joints[0].has_bounds = true;
  task.joints[0].lower = -0.5;
  task.joints[0].upper = 0.5;
  EXPECT_EQ(fesd::jointBounds(task, 0), std::make_pair(-0.5, 0.5));
}

TEST(RobotTask, ValidationNamesTheProblem) {
  fesd::TaskLimits limits;
  EXPECT_EQ(fesd::validateRobotTask(armTask(), limits), "");
  limits.max_spheres = 5;
  EXPECT_EQ(fesd::validateRobotTask(armTask(), limits), "too many collision spheres: 9 > 5");
  limits = {};
  RobotTask task = armTask();
  task.joints[2].has_bounds = true;
  task.joints[2].lower = 0.1;
  task.joints[2].upper = 1.0;
  EXPECT_EQ(fesd::validateRobotTask(task, limits),
            "joint 'wrist' starts at 0, outside its bounds [0.1, 1]");
  task = armTask();
  task.joints[0].max_velocity = std::nan("");
  EXPECT_EQ(fesd::validateRobotTask(task, limits),
            "joint 'shoulder': the velocity bound must be finite and >= 0");
  fesd::DiscScene overlapping(2);
  overlapping.bodies().push_back({"disc", 0.05, Eigen::Vector2d(0.9, 0.0), false});
  RobotTask touching(
      fesd::RobotScene(task.scene.robotPointer(), Eigen::Vector3d::Zero(), overlapping));
  EXPECT_EQ(fesd::validateRobotTask(touching, limits), "disc/hand/sphere_1 overlap at the start");
}

TEST(RobotTask, PairsBeyondReachArePruned) {
  const RobotTask task = armTask();
  bool far_seen = false, near_seen = false;
  for (const fesd::RobotPairDecision& d : fesd::decideRobotPairs(task)) {
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

TEST(RobotTask, OnlyAllowedPairsAreModelledAndOnlyThroughThemDoesAPassiveBodyMove) {
  RobotTask task = armTask();
  const std::vector<fesd::RobotPair> all = task.scene.allPairs();
  for (const fesd::RobotPair& pair : all) {
    if (task.scene.pairName(pair) == "hand/sphere_1/near_post") task.allowed_pairs.push_back(pair);
  }
  ASSERT_EQ(task.allowed_pairs.size(), 1u);
  EXPECT_EQ(task.scene.pairSides(task.allowed_pairs[0]),
            std::make_pair(std::string("hand/sphere_1"), std::string("near_post")));
  int modelled = 0;
  for (const fesd::RobotPairDecision& d : fesd::decideRobotPairs(task)) {
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

TEST(RobotTask, AFreeBodyPushedThroughOneSphereMovesAllOfThem) {
  // A bar of two spheres; only its first may meet the hand, only its second the wall beyond.
  fesd::DiscScene discs(2);
  discs.bodies().push_back({"bar", 0.1, Eigen::Vector2d(0.6, 0.3), false});
  discs.walls().push_back({"side", Eigen::Vector2d(-1.0, 0.0), -1.0});  // x <= 1
  const std::vector<fesd::FreeBodySphere> bar = {
      {"bar/sphere_0", Eigen::Vector3d(-0.05, 0.0, 0.0), 0.05},
      {"bar/sphere_1", Eigen::Vector3d(0.05, 0.0, 0.0), 0.05}};
  RobotTask task(
      fesd::RobotScene(armTask().scene.robotPointer(), Eigen::Vector3d::Zero(), discs, {bar}));
  task.horizon = 1.0;
  for (const fesd::RobotPair& pair : task.scene.allPairs()) {
    const std::string name = task.scene.pairName(pair);
    if (name == "bar/sphere_0/hand/sphere_1" || name == "bar/sphere_1/side") {
      task.allowed_pairs.push_back(pair);
    }
  }
  ASSERT_EQ(task.allowed_pairs.size(), 2u);
  const std::vector<double> reach = fesd::collisionReach(task);
  EXPECT_GT(reach[0], 0.0);
  EXPECT_EQ(reach[1], reach[0]);
  for (const fesd::RobotPairDecision& d : fesd::decideRobotPairs(task)) {
    if (task.scene.pairName(d.pair) == "bar/sphere_1/side") {
      EXPECT_TRUE(d.modelled) << d.reason;
    }
  }
}

TEST(RobotTask, OcpBoundsAndCosts) {
  RobotTask task = armTask();
  task.joints[2].target = 0.3;
  task.joints[2].target_weight = 10.0;
  const fesd::OcpDefinition ocp = fesd::buildRobotOcp(task, {});
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

TEST(RobotTask, AFreeLinkNeedsAFreeBodyOfTheScene) {
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
  const fesd::RobotTask bare(fesd::RobotScene(robot, Eigen::VectorXd::Zero(1), fesd::DiscScene(2)));
  EXPECT_EQ(fesd::validateRobotTask(bare, {}),
            "link 'puck' is on a planar or floating joint but no free body of the scene stands "
            "for it (robotForScene makes one)");
  fesd::DiscScene discs(2);
  discs.bodies().push_back({"puck", 0.1, Eigen::Vector2d(1.0, 0.0), false});
  const fesd::RobotTask with_body(fesd::RobotScene(robot, Eigen::VectorXd::Zero(1), discs));
  EXPECT_EQ(fesd::validateRobotTask(with_body, {}), "");
}

}  // namespace
