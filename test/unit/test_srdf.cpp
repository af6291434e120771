// SRDF disabled collisions (kinematics/srdf.cpp): the pairs of the shipped Panda's SRDF in file
// order; malformed, incomplete and oversized text refused with a message.
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/kinematics/srdf.h"
#include "support/robot_files.h"

namespace {

TEST(Srdf, ThePandaSrdfDisablesItsListedPairsInFileOrder) {
  const fesd::SrdfDisabledCollisions panda =
      fesd::disabledCollisionsFromSrdf(fesd_test::readRobotFile("panda.srdf"));
  ASSERT_EQ(panda.error, "");
  ASSERT_EQ(panda.pairs.size(), 34u);
  EXPECT_EQ(panda.pairs.front(),
            std::make_pair(std::string("panda_link0"), std::string("panda_link1")));
  EXPECT_EQ(panda.pairs[4], std::make_pair(std::string("panda_link1"), std::string("panda_link2")));
}

TEST(Srdf, MalformedIncompleteAndOversizedTextIsRefused) {
  EXPECT_EQ(fesd::disabledCollisionsFromSrdf("<robot name='r'/>").pairs.size(), 0u);
  EXPECT_NE(fesd::disabledCollisionsFromSrdf("<robot name='r'><disable").error.find("malformed"),
            std::string::npos);
  EXPECT_NE(fesd::disabledCollisionsFromSrdf("<other/>").error.find("no <robot>"),
            std::string::npos);
  const fesd::SrdfDisabledCollisions incomplete = fesd::disabledCollisionsFromSrdf(
      "<robot name='r'>\n<disable_collisions link1='a' link2='b'/>\n"
      "<disable_collisions link1='a'/></robot>");
  EXPECT_EQ(incomplete.error,
            "malformed SRDF: a <disable_collisions> on line 3 lacks link1 or link2");
  EXPECT_TRUE(incomplete.pairs.empty());
  const std::string big = "<robot name='r'>" + std::string(2000, ' ') + "</robot>";
  EXPECT_EQ(fesd::disabledCollisionsFromSrdf(big, 1000).error,
            "the SRDF has 2024 bytes, more than 1000");
  EXPECT_EQ(fesd::disabledCollisionsFromSrdf(big, 4000).error, "");
}

}  // namespace
