// Scenes from URDF (scene/urdf_scene.cpp): spheres and upright cylinders become bodies, fixed
// links obstacles, in the plane and in space; malformed XML is refused with a message.
#include <cmath>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/scene/urdf_scene.h"

namespace {

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

}  // namespace

namespace {

// A serial chain of `links` links on revolute joints, each with a sphere 1 beyond its parent.
std::string chainUrdf(int links) {
  std::ostringstream xml;
  xml << "<robot name=\"chain\"><link name=\"l0\"/>";
  for (int i = 1; i < links; ++i) {
    xml << "<link name=\"l" << i << "\"><collision><geometry><sphere radius=\"0.1\"/></geometry>"
        << "</collision></link><joint name=\"j" << i << "\" type=\"continuous\"><parent link=\"l"
        << i - 1 << "\"/><child link=\"l" << i << "\"/><origin xyz=\"1 0 0\"/>"
        << "<axis xyz=\"0 0 1\"/></joint>";
  }
  xml << "</robot>";
  return xml.str();
}

}  // namespace

TEST(UrdfScene, ALongChainIsRefusedBeforeItIsWalked) {
  const fesd::UrdfScene refused = fesd::sceneFromUrdf(chainUrdf(20000), true);
  EXPECT_NE(refused.error.find("too many links: 20000 > 2000"), std::string::npos) << refused.error;
  fesd::UrdfLimits small_files;
  small_files.max_bytes = 1000;
  EXPECT_NE(fesd::sceneFromUrdf(chainUrdf(100), true, small_files).error.find("URDF too large"),
            std::string::npos);
}

TEST(UrdfScene, AChainDeeperThanAnyCallStackIsWalkedInOrder) {
  // 20000 links deep: a recursive walk (one stack frame per link) crashed the node here.
  fesd::UrdfLimits generous;
  generous.max_links = 30000;
  const fesd::UrdfScene chain = fesd::sceneFromUrdf(chainUrdf(20000), true, generous);
  ASSERT_TRUE(chain.error.empty()) << chain.error;
  ASSERT_EQ(chain.scene.bodies().size(), 19999u);
  EXPECT_EQ(chain.scene.bodies().front().name, "l1");
  EXPECT_EQ(chain.scene.bodies().back().name, "l19999");
  EXPECT_DOUBLE_EQ(chain.scene.bodies().back().position.x(), 19999.0);
}

namespace {

// A link of three spheres (an L) on a planar joint whose frame is turned by 0.5 rad about z
// (and by `roll` about x: pi turns its z down), its axis `axis_z` (+1 or -1) along its z.
std::string planarLinkUrdf(int axis_z, double roll) {
  std::ostringstream xml;
  xml.precision(17);
  xml << R"(<robot name="r"><link name="world"/>
    <link name="l">
      <collision><origin xyz="0.2 0 0"/><geometry><sphere radius="0.1"/></geometry></collision>
      <collision><origin xyz="0.4 0 0"/><geometry><sphere radius="0.1"/></geometry></collision>
      <collision><origin xyz="0.2 0.3 0"/><geometry><sphere radius="0.15"/></geometry></collision>
      <collision><geometry><box size="1 1 1"/></geometry></collision>
    </link>
    <joint name="slide" type="planar"><parent link="world"/><child link="l"/>
      <origin xyz="1 2 0" rpy=")"
      << roll << R"( 0 0.5"/><axis xyz="0 0 )" << axis_z << R"("/></joint></robot>)";
  return xml.str();
}

// The spheres' centres of planarLinkUrdf at joint coordinates (x, y, theta), by its kinematics:
// theta about the joint frame's z, as MoveIt reads a planar joint.
std::vector<Eigen::Vector2d> planarLinkSpheres(const Eigen::Vector3d& joint, double roll) {
  const Eigen::Isometry3d link = Eigen::Translation3d(1.0, 2.0, 0.0) *
                                 Eigen::AngleAxisd(0.5, Eigen::Vector3d::UnitZ()) *
                                 Eigen::AngleAxisd(roll, Eigen::Vector3d::UnitX()) *
                                 Eigen::Translation3d(joint.x(), joint.y(), 0.0) *
                                 Eigen::AngleAxisd(joint.z(), Eigen::Vector3d::UnitZ());
  std::vector<Eigen::Vector2d> centres;
  for (const Eigen::Vector3d& local :
       {Eigen::Vector3d(0.2, 0.0, 0.0), Eigen::Vector3d(0.4, 0.0, 0.0),
        Eigen::Vector3d(0.2, 0.3, 0.0)}) {
    centres.push_back((link * local).head<2>());
  }
  return centres;
}

}  // namespace

TEST(UrdfScene, ALinkOfSpheresOnAPlanarJointTurnsAndMapsBackToItsJoint) {
  for (const auto& [axis_z, roll] :
       std::vector<std::pair<int, double>>{{1, 0.0}, {-1, 0.0}, {1, M_PI}}) {
    SCOPED_TRACE("axis " + std::to_string(axis_z) + ", roll " + std::to_string(roll));
    const fesd::UrdfScene read = fesd::sceneFromUrdf(planarLinkUrdf(axis_z, roll), true);
    ASSERT_EQ(read.error, "");
    EXPECT_EQ(read.ignored_shapes, std::vector<std::string>{"l/collision_3"});
    ASSERT_EQ(read.scene.bodies().size(), 1u);
    const fesd::SceneBody& body = read.scene.bodies()[0];
    EXPECT_TRUE(body.turns);
    EXPECT_EQ(body.yaw, 0.0);
    ASSERT_EQ(body.spheres.size(), 3u);
    EXPECT_EQ(body.spheres[2].name, "l/sphere_2");
    EXPECT_GT(body.turning_radius, 0.0);
    ASSERT_EQ(read.planar_joints.size(), 1u);
    const fesd::UrdfPlanarJoint& joint = read.planar_joints[0];
    EXPECT_EQ(joint.joint, "slide");
    EXPECT_EQ(joint.body, 0);
    EXPECT_EQ(joint.turn_sign, roll == 0.0 ? 1.0 : -1.0);
    EXPECT_LT(fesd::planarJointValues(joint, body.position, 0.0).norm(), 1e-14);

    // The body placed on the kinematics' spheres at some joint coordinates: every sphere where
    // the URDF puts it, and the coordinates recovered from the body's position and yaw.
    const Eigen::Vector3d coordinates(0.3, -0.2, 0.7);
    const std::vector<Eigen::Vector2d> centres = planarLinkSpheres(coordinates, roll);
    const double yaw = joint.turn_sign * coordinates.z();
    const Eigen::Rotation2Dd turn(yaw);
    const Eigen::Vector2d position = centres[0] - turn * body.spheres[0].offset.head<2>();
    for (size_t k = 0; k < 3; ++k) {
      EXPECT_LT((position + turn * body.spheres[k].offset.head<2>() - centres[k]).norm(), 1e-14)
          << "sphere " << k;
    }
    EXPECT_LT((fesd::planarJointValues(joint, position, yaw) - coordinates).norm(), 1e-14);
  }
}

TEST(UrdfScene, SpheresBelowATurningLinkAreRefused) {
  std::string urdf = planarLinkUrdf(1, 0.0);
  urdf.replace(urdf.find("</robot>"), 8, R"(<link name="handle">
      <collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <joint name="weld" type="fixed"><parent link="l"/><child link="handle"/></joint></robot>)");
  const std::string error = fesd::sceneFromUrdf(urdf, true).error;
  EXPECT_NE(error.find("'handle' hangs from 'l'"), std::string::npos) << error;
}

TEST(UrdfScene, SeveralSpheresOfAFixedLinkAreObstaclesAndOfAFloatingOneABodyThatTranslates) {
  const std::string urdf = R"(<robot name="r"><link name="world"/>
    <link name="rail">
      <collision><origin xyz="0 0 0"/><geometry><sphere radius="0.1"/></geometry></collision>
      <collision><origin xyz="1 0 0"/><geometry><sphere radius="0.2"/></geometry></collision>
    </link>
    <joint name="jr" type="fixed"><parent link="world"/><child link="rail"/></joint>
    <link name="bar">
      <collision><origin xyz="0 0 0"/><geometry><sphere radius="0.1"/></geometry></collision>
      <collision><origin xyz="0 1 0"/><geometry><sphere radius="0.1"/></geometry></collision>
    </link>
    <joint name="jb" type="floating"><parent link="world"/><child link="bar"/>
      <origin xyz="3 0 0"/></joint>
  </robot>)";
  const fesd::UrdfScene read = fesd::sceneFromUrdf(urdf, true);
  ASSERT_EQ(read.error, "");
  ASSERT_EQ(read.scene.obstacles().size(), 2u);
  EXPECT_EQ(read.scene.obstacles()[1].name, "rail/sphere_1");
  EXPECT_EQ(read.scene.obstacles()[1].radius, 0.2);
  EXPECT_TRUE(read.scene.obstacles()[1].position.isApprox(Eigen::Vector2d(1.0, 0.0)));
  ASSERT_EQ(read.scene.bodies().size(), 1u);
  const fesd::SceneBody& bar = read.scene.bodies()[0];
  EXPECT_FALSE(bar.turns);
  EXPECT_TRUE(bar.position.isApprox(Eigen::Vector2d(3.0, 0.5)));
  ASSERT_EQ(bar.spheres.size(), 2u);
  EXPECT_TRUE(bar.spheres[1].offset.isApprox(Eigen::Vector3d(0.0, 0.5, 0.0)));
  EXPECT_DOUBLE_EQ(bar.radius, 0.6);
  EXPECT_TRUE(read.planar_joints.empty());  // a floating joint is answered by the body alone
}
