// Robots read for scenes (scene/robot_from_urdf.cpp): planarity inferred, forced planar refused
// naming the joint that leaves the plane, forced spatial taken, free links as free bodies.
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/scene/robot_from_urdf.h"
#include "support/robot_files.h"

namespace {

using fesd::PlanarChoice;

TEST(RobotFromUrdf, PlanarityIsInferred) {
  const fesd::RobotForScene arm =
      fesd::robotForScene(fesd_test::readRobotFile("planar_arm.urdf"), PlanarChoice::kInferred);
  ASSERT_EQ(arm.error, "");
  EXPECT_EQ(arm.dimension, 2);
  EXPECT_EQ(arm.robot->numCoordinates(), 3);
  const fesd::RobotForScene panda = fesd::robotForScene(
      fesd_test::readRobotFile("panda_spherized.urdf"), PlanarChoice::kInferred);
  ASSERT_EQ(panda.error, "");
  EXPECT_EQ(panda.dimension, 3);
  EXPECT_EQ(panda.robot->numCoordinates(), 7);  // VAMP fixes the fingers
}

TEST(RobotFromUrdf, ForcingPlanarOnASpatialRobotNamesTheJoint) {
  const fesd::RobotForScene panda =
      fesd::robotForScene(fesd_test::readRobotFile("panda_spherized.urdf"), PlanarChoice::kPlanar);
  EXPECT_EQ(panda.robot, nullptr);
  EXPECT_EQ(panda.error,
            "the scene cannot be planar: joint 'panda_joint2' moves the robot out of the (x, y) "
            "plane");
  const fesd::RobotForScene arm =
      fesd::robotForScene(fesd_test::readRobotFile("planar_arm.urdf"), PlanarChoice::kSpatial);
  ASSERT_EQ(arm.error, "");
  EXPECT_EQ(arm.dimension, 3);
}

/// A one-joint arm and a puck on a free joint of the world; `puck` is the puck link's body,
/// `joint` its joint's type.
std::string armAndPuck(const std::string& puck, const std::string& joint = "floating",
                       const std::string& parent = "world") {
  return R"(<robot name="arm_and_puck"><link name="world"/>
    <link name="arm"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <joint name="hinge" type="revolute"><parent link="world"/><child link="arm"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <link name="puck">)" +
         puck + R"(</link>
    <joint name="loose" type=")" +
         joint + R"("><parent link=")" + parent + R"("/><child link="puck"/>
      <origin xyz="0.6 0.2 0"/><axis xyz="0 0 1"/></joint></robot>)";
}

const std::string kSphere =
    R"(<collision><origin xyz="0 0.1 0"/><geometry><sphere radius="0.05"/></geometry></collision>)";

TEST(RobotFromUrdf, AFreeLinkWithOneSphereIsAFreeBodyAtItsUrdfPose) {
  for (const std::string joint : {"floating", "planar"}) {
    const fesd::RobotForScene read =
        fesd::robotForScene(armAndPuck(kSphere, joint), PlanarChoice::kInferred);
    ASSERT_EQ(read.error, "") << joint;
    EXPECT_EQ(read.dimension, 2);
    EXPECT_EQ(read.robot->numCoordinates(), 1);
    ASSERT_EQ(read.free_bodies.size(), 1u);
    const fesd::SceneBody& puck = read.free_bodies[0];
    EXPECT_EQ(puck.name, "puck");
    EXPECT_EQ(puck.radius, 0.05);
    EXPECT_FALSE(puck.actuated);
    EXPECT_TRUE(puck.position.isApprox(Eigen::Vector2d(0.6, 0.3), 1e-12)) << puck.position;
  }
  const fesd::RobotForScene spatial =
      fesd::robotForScene(armAndPuck(kSphere), PlanarChoice::kSpatial);
  ASSERT_EQ(spatial.error, "");
  ASSERT_EQ(spatial.free_bodies.size(), 1u);
  EXPECT_TRUE(spatial.free_bodies[0].position.isApprox(Eigen::Vector3d(0.6, 0.3, 0.0), 1e-12));
}

TEST(RobotFromUrdf, AFreeLinkWithSeveralSpheresIsOneBodyAtTheirMeanThatBoundsThem) {
  // Spheres at (0, 0.1) and (0.2, 0.1) about the link's origin (0.6, 0.2), and a box (ignored).
  const std::string bar =
      kSphere + R"(<collision><origin xyz="0.2 0.1 0"/><geometry><sphere radius="0.03"/>
      </geometry></collision><collision><geometry><box size="1 1 1"/></geometry></collision>)";
  for (const PlanarChoice choice : {PlanarChoice::kInferred, PlanarChoice::kSpatial}) {
    const fesd::RobotForScene read = fesd::robotForScene(armAndPuck(bar), choice);
    ASSERT_EQ(read.error, "");
    const int dim = read.dimension;
    ASSERT_EQ(read.free_bodies.size(), 1u);
    const fesd::SceneBody& body = read.free_bodies[0];
    EXPECT_EQ(body.name, "puck");
    EXPECT_FALSE(body.actuated);
    const Eigen::VectorXd mean = (Eigen::VectorXd(3) << 0.7, 0.3, 0.0).finished().head(dim);
    EXPECT_TRUE(body.position.isApprox(mean, 1e-12)) << body.position;
    EXPECT_NEAR(body.radius, 0.1 + 0.05, 1e-12);  // the first sphere's far side
    const std::vector<fesd::FreeBodySphere>& spheres = body.spheres;
    ASSERT_EQ(spheres.size(), 2u);
    EXPECT_EQ(spheres[0].name, "puck/sphere_0");
    EXPECT_EQ(spheres[1].name, "puck/sphere_1");
    EXPECT_TRUE(spheres[0].offset.isApprox(Eigen::Vector3d(-0.1, 0.0, 0.0), 1e-12));
    EXPECT_TRUE(spheres[1].offset.isApprox(Eigen::Vector3d(0.1, 0.0, 0.0), 1e-12));
    EXPECT_EQ(spheres[1].radius, 0.03);
    EXPECT_EQ(read.robot->ignored_shapes, std::vector<std::string>{"puck/collision_2 (box)"});
  }
  // One sphere: the body is that sphere, with no sphere list.
  const fesd::RobotForScene one = fesd::robotForScene(armAndPuck(kSphere), PlanarChoice::kInferred);
  ASSERT_EQ(one.free_bodies.size(), 1u);
  EXPECT_TRUE(one.free_bodies[0].spheres.empty());
}

TEST(RobotFromUrdf, AFreeLinkUnderAnOffsetTurnedLinkIsPlacedInTheWorld) {
  // The table sits at (1, 0, 0) turned 90 degrees about z; the puck's joint at (0.6, 0.2, 0) on
  // it and its sphere 0.1 along the puck's y: (1, 0, 0) + Rz (0.6, 0.3, 0) = (0.7, 0.6, 0).
  const auto urdf = [](const std::string& joint, const std::string& table_rpy) {
    return R"(<robot name="r"><link name="world"/>
    <link name="arm"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <joint name="hinge" type="revolute"><parent link="world"/><child link="arm"/>
      <axis xyz="0 0 1"/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
    <link name="table"/>
    <joint name="stand" type="fixed"><parent link="world"/><child link="table"/>
      <origin xyz="1 0 0" rpy=")" +
           table_rpy + R"("/></joint>
    <link name="puck">)" +
           kSphere + R"(</link>
    <joint name="loose" type=")" +
           joint + R"("><parent link="table"/><child link="puck"/>
      <origin xyz="0.6 0.2 0"/><axis xyz="0 0 1"/></joint></robot>)";
  };
  for (const std::string joint : {"floating", "planar"}) {
    const fesd::RobotForScene read =
        fesd::robotForScene(urdf(joint, "0 0 1.5707963267948966"), PlanarChoice::kInferred);
    ASSERT_EQ(read.error, "") << joint;
    ASSERT_EQ(read.free_bodies.size(), 1u);
    EXPECT_TRUE(read.free_bodies[0].position.isApprox(Eigen::Vector2d(0.7, 0.6), 1e-12))
        << read.free_bodies[0].position;
  }
  // Turned about x, the planar joint's normal lies in the scene's plane.
  EXPECT_EQ(
      fesd::robotForScene(urdf("planar", "1.5707963267948966 0 0"), PlanarChoice::kInferred).error,
      "free link 'puck' (joint 'loose') slides in a plane other than the scene's (x, y): "
      "its normal must be z");
}

TEST(RobotFromUrdf, AFreeLinkNoBodyCanStandForIsRefusedByName) {
  const auto error = [](const std::string& urdf, PlanarChoice choice = PlanarChoice::kInferred) {
    return fesd::robotForScene(urdf, choice).error;
  };
  EXPECT_EQ(error(armAndPuck(R"(<collision><geometry><box size="0.1 0.1 0.1"/></geometry>
      </collision>)")),
            "free link 'puck' (joint 'loose') has no collision sphere (or cylinder normal to the "
            "plane): a free link needs one to be a body");
  EXPECT_EQ(error(armAndPuck(""), PlanarChoice::kSpatial),
            "free link 'puck' (joint 'loose') has no collision sphere: a free link needs one to "
            "be a body");
  EXPECT_EQ(error(armAndPuck(kSphere, "floating", "arm")),
            "free link 'puck' (joint 'loose') hangs from a moving link: only free links of the "
            "world are modelled");
  EXPECT_EQ(error(armAndPuck(kSphere, "planar"), PlanarChoice::kSpatial),
            "free link 'puck' (joint 'loose') is planar in a spatial scene: its plane is not "
            "modelled");
  std::string tilted = armAndPuck(kSphere, "planar");
  tilted.replace(tilted.find(R"(<axis xyz="0 0 1"/></joint></robot>)"), 17,
                 R"(<axis xyz="1 0 0"/>)");
  EXPECT_EQ(error(tilted),
            "free link 'puck' (joint 'loose') slides in a plane other than the scene's (x, y): "
            "its normal must be z");
  std::string with_child = armAndPuck(kSphere);
  with_child.replace(with_child.rfind("</robot>"), 8, R"(<link name="lid"/>
    <joint name="glued" type="fixed"><parent link="puck"/><child link="lid"/></joint></robot>)");
  EXPECT_EQ(error(with_child),
            "free link 'puck' (joint 'loose') has links below it: a free link is modelled as one "
            "body");
}

TEST(RobotFromUrdf, BrokenUrdfIsRefused) {
  const fesd::RobotForScene broken = fesd::robotForScene("<robot", PlanarChoice::kInferred);
  EXPECT_EQ(broken.robot, nullptr);
  EXPECT_FALSE(broken.error.empty());
}

}  // namespace
