// The kinematic model read from URDF (kinematics/kinematic_model.cpp): coordinates, limits,
// normalised axes, every collision sphere by name, free links, ignored shapes, and bounded input
// (too many links, joints or spheres refused; long chains walked without recursion).
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "fesd_trajopt/kinematics/kinematic_model.h"
#include "support/robot_files.h"

namespace {

/// A serial chain of `links` links, each 0.01 m beyond the last, on joints of the given type.
std::string chainUrdf(int links, const std::string& joint_type) {
  std::string xml = "<robot name='chain'><link name='l0'/>";
  for (int i = 1; i < links; ++i) {
    const std::string link = "l" + std::to_string(i);
    xml += "<link name='" + link + "'><collision><geometry><sphere radius='0.001'/></geometry>" +
           "</collision></link><joint name='j" + std::to_string(i) + "' type='" + joint_type +
           "'><parent link='l" + std::to_string(i - 1) + "'/><child link='" + link +
           "'/><origin xyz='0.01 0 0'/><axis xyz='0 0 1'/>" +
           "<limit lower='-1' upper='1' effort='1' velocity='1'/></joint>";
  }
  return xml + "</robot>";
}

TEST(KinematicModel, PlanarArmHasThreeRevoluteJointsAndNineNamedSpheres) {
  const fesd::KinematicModel arm = fesd_test::loadShippedRobot("planar_arm.urdf");
  ASSERT_EQ(arm.numCoordinates(), 3);
  EXPECT_EQ(arm.root_link, "base");
  const std::vector<std::string> names{"shoulder", "elbow", "wrist"};
  const std::vector<double> velocities{1.0, 1.5, 2.0};
  for (int j = 0; j < 3; ++j) {
    EXPECT_EQ(arm.joints[j].name, names[j]);
    EXPECT_EQ(arm.joints[j].type, fesd::JointType::kRevolute);
    EXPECT_EQ(arm.joints[j].parent, j - 1);
    EXPECT_EQ(arm.joints[j].max_velocity, velocities[j]);
    EXPECT_TRUE(arm.joints[j].axis.isApprox(Eigen::Vector3d::UnitZ()));
  }
  EXPECT_EQ(arm.joints[0].lower, -2.8);
  EXPECT_EQ(arm.joints[0].upper, 2.8);
  ASSERT_EQ(arm.spheres.size(), 9u);
  const int sphere = arm.sphereIndex("forearm/sphere_2");
  ASSERT_GE(sphere, 0);
  EXPECT_EQ(arm.links[arm.spheres[sphere].link].name, "forearm");
  EXPECT_EQ(arm.spheres[sphere].radius, 0.04);
  EXPECT_TRUE(arm.spheres[sphere].local_centre.isApprox(Eigen::Vector3d(0.2, 0.0, 0.0)));
  EXPECT_EQ(arm.chainOf(sphere), (std::vector<int>{0, 1}));
  EXPECT_TRUE(arm.chainOf(arm.sphereIndex("base/sphere_0")).empty());
  EXPECT_TRUE(arm.ignored_shapes.empty());
  EXPECT_TRUE(arm.free_links.empty());
}

TEST(KinematicModel, PandaHasSevenRevoluteJointsAndFiftyNineSpheres) {
  const fesd::KinematicModel panda = fesd_test::loadShippedRobot("panda_spherized.urdf");
  ASSERT_EQ(panda.numCoordinates(), 7);
  for (int j = 0; j < 7; ++j) {
    EXPECT_EQ(panda.joints[j].name, "panda_joint" + std::to_string(j + 1));
    EXPECT_EQ(panda.joints[j].chain.size(), static_cast<std::size_t>(j + 1));
  }
  EXPECT_EQ(panda.joints[4].max_velocity, 2.871);
  EXPECT_EQ(panda.joints[3].upper, 0.0873);
  EXPECT_EQ(panda.spheres.size(), 59u);
  // The fingers hang from joint 7 through fixed joints.
  const int finger = panda.sphereIndex("panda_leftfinger/sphere_1");
  ASSERT_GE(finger, 0);
  EXPECT_EQ(panda.chainOf(finger).size(), 7u);
}

TEST(KinematicModel, AxesAreNormalisedContinuousJointsUnboundedAndBadJointsRefused) {
  const fesd::KinematicModelResult mixed = fesd::buildKinematicModel(fesd_test::mixedJointsUrdf());
  ASSERT_EQ(mixed.error, "");
  const fesd::KinematicModel& model = mixed.model;
  ASSERT_EQ(model.numCoordinates(), 4);
  const fesd::KinematicJoint& turn = model.joints[model.jointIndex("turn")];
  EXPECT_TRUE(turn.axis.isApprox(Eigen::Vector3d(1.0, 1.0, 0.0) / std::sqrt(2.0)));
  const fesd::KinematicJoint& slide = model.joints[model.jointIndex("slide")];
  EXPECT_EQ(slide.type, fesd::JointType::kPrismatic);
  EXPECT_TRUE(slide.axis.isApprox(Eigen::Vector3d::UnitZ()));
  const fesd::KinematicJoint& spin = model.joints[model.jointIndex("spin")];
  EXPECT_EQ(spin.type, fesd::JointType::kContinuous);
  EXPECT_TRUE(std::isinf(spin.lower) && spin.lower < 0.0 && std::isinf(spin.upper));
  EXPECT_EQ(spin.max_velocity, 0.0);  // no <limit>: the caller applies its default
  // The sphere of the fixed-joint link b_tool moves with the prismatic joint.
  const int tool = model.sphereIndex("b_tool/sphere_0");
  EXPECT_EQ(model.links[model.spheres[tool].link].joint, model.jointIndex("slide"));
  EXPECT_EQ(model.ignored_shapes, std::vector<std::string>{"a/collision_1 (box)"});

  const std::string zero_axis = R"(<robot name="r"><link name="a"/><link name="b"/>
    <joint name="bad" type="continuous"><parent link="a"/><child link="b"/>
      <axis xyz="0 0 0"/></joint></robot>)";
  EXPECT_EQ(fesd::buildKinematicModel(zero_axis).error, "joint bad has a zero axis");
  const std::string reversed_limits = R"(<robot name="r"><link name="a"/><link name="b"/>
    <joint name="bad" type="revolute"><parent link="a"/><child link="b"/><axis xyz="0 0 1"/>
      <limit lower="1" upper="-1" effort="1" velocity="1"/></joint></robot>)";
  EXPECT_EQ(fesd::buildKinematicModel(reversed_limits).error,
            "joint bad has limits out of order or a negative velocity limit");
  EXPECT_NE(fesd::buildKinematicModel("<robot name='x'><link name=").error.find("malformed"),
            std::string::npos);
}

TEST(KinematicModel, FreeLinksAreReportedAndUprightCylindersAreDiscsInPlanarModels) {
  const std::string urdf = R"(<robot name="r"><link name="world"/>
    <link name="puck"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <joint name="slide" type="planar"><parent link="world"/><child link="puck"/>
      <axis xyz="0 0 1"/></joint>
    <link name="ball"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <joint name="fly" type="floating"><parent link="world"/><child link="ball"/></joint>
    <link name="post">
      <collision><origin xyz="1 0 0"/><geometry><cylinder radius="0.2" length="1"/></geometry>
      </collision>
      <collision><origin rpy="1.5707963 0 0"/><geometry><cylinder radius="0.3" length="1"/>
      </geometry></collision></link>
    <joint name="hinge" type="continuous"><parent link="world"/><child link="post"/>
      <axis xyz="0 0 1"/></joint></robot>)";
  fesd::KinematicModelOptions options;
  options.planar = true;
  const fesd::KinematicModelResult planar = fesd::buildKinematicModel(urdf, options);
  ASSERT_EQ(planar.error, "");
  ASSERT_EQ(planar.model.free_links.size(), 2u);
  EXPECT_EQ(planar.model.free_links[0].link, "ball");
  EXPECT_FALSE(planar.model.free_links[0].planar);
  EXPECT_EQ(planar.model.free_links[1].joint, "slide");
  EXPECT_TRUE(planar.model.free_links[1].planar);
  EXPECT_EQ(planar.model.free_links[1].parent_link, "world");
  EXPECT_EQ(planar.model.numCoordinates(), 1);
  ASSERT_EQ(planar.model.free_links[1].spheres.size(), 1u);  // the free link's own
  EXPECT_EQ(planar.model.free_links[1].spheres[0].name, "puck/sphere_0");
  EXPECT_EQ(planar.model.free_links[1].spheres[0].link, -1);
  ASSERT_EQ(planar.model.spheres.size(), 1u);  // free links' spheres are the scene's
  EXPECT_EQ(planar.model.spheres[0].name, "post/sphere_0");
  EXPECT_EQ(planar.model.spheres[0].radius, 0.2);
  EXPECT_EQ(planar.model.ignored_shapes, std::vector<std::string>{"post/collision_1 (cylinder)"});

  const fesd::KinematicModelResult spatial = fesd::buildKinematicModel(urdf);
  EXPECT_TRUE(spatial.model.spheres.empty());
  EXPECT_EQ(spatial.model.ignored_shapes.size(), 2u);
}

TEST(KinematicModel, OversizedInputIsRefusedAndLongChainsAreWalkedWithoutRecursion) {
  const std::string long_chain = chainUrdf(20000, "fixed");
  EXPECT_EQ(fesd::buildKinematicModel(long_chain).error,
            "the URDF has 20000 links, more than 1000");

  // Allowed, the same chain is walked iteratively: its last sphere lands 199.99 m out.
  fesd::KinematicModelOptions generous;
  generous.max_links = 20000;
  generous.max_spheres = 20000;
  const fesd::KinematicModelResult walked = fesd::buildKinematicModel(long_chain, generous);
  ASSERT_EQ(walked.error, "");
  ASSERT_EQ(walked.model.spheres.size(), 19999u);
  fesd::KinematicData data;
  fesd::forwardKinematics(walked.model, Eigen::VectorXd(0), data);
  EXPECT_NEAR(data.sphere_centres.back().x(), 199.99, 1e-9);

  generous.max_spheres = 100;
  EXPECT_EQ(fesd::buildKinematicModel(chainUrdf(200, "fixed"), generous).error,
            "the URDF has more than 100 collision spheres (limits/max_spheres)");
  EXPECT_EQ(fesd::buildKinematicModel(chainUrdf(200, "revolute"), generous).error,
            "the URDF has more than 64 moving joints");
  // A free link's spheres count too.
  std::string ball = R"(<robot name="r"><link name="world"/><link name="ball">)";
  for (int k = 0; k < 3; ++k) {
    ball += R"(<collision><geometry><sphere radius="0.1"/></geometry></collision>)";
  }
  ball += R"(</link><joint name="fly" type="floating"><parent link="world"/>
    <child link="ball"/></joint></robot>)";
  generous.max_spheres = 2;
  EXPECT_EQ(fesd::buildKinematicModel(ball, generous).error,
            "the URDF has more than 2 collision spheres (limits/max_spheres)");
}

}  // namespace
