#include "support/robot_files.h"

#include <fstream>
#include <sstream>

#include <gtest/gtest.h>

namespace fesd_test {

std::string readRobotFile(const std::string& name) {
  std::ifstream file(std::string(FESD_ROBOTS_DIR) + "/" + name);
  std::stringstream text;
  text << file.rdbuf();
  return text.str();
}

std::string mixedJointsUrdf() {
  return R"(<robot name="mixed">
    <link name="base"><collision><geometry><sphere radius="0.1"/></geometry></collision></link>
    <link name="a">
      <collision><origin xyz="0.2 0.1 0"/><geometry><sphere radius="0.05"/></geometry></collision>
      <collision><geometry><box size="0.1 0.1 0.1"/></geometry></collision></link>
    <link name="b">
      <collision><origin xyz="0 0.3 0.1"/><geometry><sphere radius="0.04"/></geometry></collision>
    </link>
    <link name="b_tool">
      <collision><origin xyz="0.1 0 0.05"/><geometry><sphere radius="0.03"/></geometry></collision>
    </link>
    <link name="c">
      <collision><origin xyz="0.1 -0.2 0.3"/><geometry><sphere radius="0.02"/></geometry></collision>
    </link>
    <link name="d">
      <collision><origin xyz="0.3 0 0"/><geometry><sphere radius="0.06"/></geometry></collision>
    </link>
    <joint name="turn" type="revolute"><parent link="base"/><child link="a"/>
      <origin xyz="0.1 0 0.2" rpy="0.3 0 0"/><axis xyz="1 1 0"/>
      <limit lower="-2" upper="2" effort="1" velocity="0.5"/></joint>
    <joint name="slide" type="prismatic"><parent link="a"/><child link="b"/>
      <origin xyz="0.3 0 0" rpy="0 0.4 0.2"/><axis xyz="0 0 2"/>
      <limit lower="-0.5" upper="0.5" effort="1" velocity="0.2"/></joint>
    <joint name="tool" type="fixed"><parent link="b"/><child link="b_tool"/>
      <origin xyz="0 0.1 0" rpy="0.5 -0.3 0.1"/></joint>
    <joint name="spin" type="continuous"><parent link="b_tool"/><child link="c"/>
      <origin xyz="0.2 0 0" rpy="0 0 0.7"/><axis xyz="0 1 0"/></joint>
    <joint name="branch" type="revolute"><parent link="a"/><child link="d"/>
      <origin xyz="0 -0.2 0"/><axis xyz="0 0 -1"/>
      <limit lower="-1" upper="1" effort="1" velocity="1"/></joint>
  </robot>)";
}

fesd::KinematicModel loadShippedRobot(const std::string& name) {
  fesd::KinematicModelResult result = fesd::buildKinematicModel(readRobotFile(name));
  EXPECT_EQ(result.error, "") << name;
  return std::move(result.model);
}

}  // namespace fesd_test
