// Planarity (kinematics/planarity.cpp): a robot is planar in (x, y) when no joint that moves a
// sphere can take it out of the plane; otherwise the first such joint is named.
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/kinematics/planarity.h"
#include "support/robot_files.h"

namespace {

/// One joint of the given type and axis, below a fixed joint turned by rpy, moving a sphere.
std::string oneJointUrdf(const std::string& type, const std::string& axis, const std::string& rpy,
                         bool sphere = true) {
  return R"(<robot name="r"><link name="base"/><link name="mount"/><link name="arm">)" +
         std::string(sphere ? R"(<collision><origin xyz="0.3 0.1 0"/>
           <geometry><sphere radius="0.1"/></geometry></collision>)"
                            : "") +
         R"(</link><joint name="mount" type="fixed"><parent link="base"/><child link="mount"/>
           <origin rpy=")" +
         rpy + R"("/></joint>
         <joint name="moving" type=")" +
         type + R"("><parent link="mount"/><child link="arm"/><axis xyz=")" + axis +
         R"("/><limit lower="-1" upper="1" effort="1" velocity="1"/></joint></robot>)";
}

std::string firstOffender(const std::string& urdf) {
  const fesd::KinematicModelResult result = fesd::buildKinematicModel(urdf);
  EXPECT_EQ(result.error, "");
  return fesd::firstJointLeavingPlane(result.model);
}

TEST(KinematicPlanarity, ThePlanarArmIsPlanarAndThePandaLeavesThePlaneAtItsSecondJoint) {
  EXPECT_TRUE(fesd::isPlanar(fesd_test::loadShippedRobot("planar_arm.urdf")));
  const fesd::KinematicModel panda = fesd_test::loadShippedRobot("panda_spherized.urdf");
  EXPECT_FALSE(fesd::isPlanar(panda));
  EXPECT_EQ(fesd::firstJointLeavingPlane(panda), "panda_joint2");  // joint 1 turns about z
}

TEST(KinematicPlanarity, AxesCountInTheWorldAfterTheFixedRotationsAbove) {
  EXPECT_EQ(firstOffender(oneJointUrdf("revolute", "0 0 -1", "0 0 0.5")), "");
  EXPECT_EQ(firstOffender(oneJointUrdf("revolute", "0 0 1", "0.3 0 0")), "moving");
  // Turned a quarter about x, a y axis points along z.
  EXPECT_EQ(firstOffender(oneJointUrdf("revolute", "0 1 0", "1.5707963267948966 0 0")), "");
  EXPECT_EQ(firstOffender(oneJointUrdf("prismatic", "1 1 0", "0 0 0.2")), "");
  EXPECT_EQ(firstOffender(oneJointUrdf("prismatic", "0 0 1", "0 0 0")), "moving");
  EXPECT_EQ(firstOffender(oneJointUrdf("continuous", "1 0 0", "0 0 0")), "moving");
  // A joint that moves no sphere cannot take one out of the plane.
  EXPECT_EQ(firstOffender(oneJointUrdf("continuous", "1 0 0", "0 0 0", false)), "");
  EXPECT_EQ(firstOffender(fesd_test::mixedJointsUrdf()), "turn");
}

}  // namespace
