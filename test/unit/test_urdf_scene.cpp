// Scenes from URDF (scene/urdf_scene.cpp): spheres and upright cylinders become bodies, fixed
// links obstacles, in the plane and in space; malformed XML is refused with a message.
#include <sstream>
#include <string>
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
