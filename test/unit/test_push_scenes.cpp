// The random push scenes (examples/push_scenes.cpp): a seed gives the same scene on every machine,
// and the sweep's outlier rule. The sweep itself: regression/test_push_scene_sweep.cpp.
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/push_scenes.h"

namespace {

namespace ps = fesd::push_scenes;

TEST(PushScenes, TheScenesAreTheSameOnEveryMachine) {
  const ps::PushScene scene = ps::randomPushScene(1);
  EXPECT_EQ(scene.scene.dimension(), 2);
  EXPECT_EQ(scene.scene.bodies().size(), 3u);
  EXPECT_NEAR(scene.contact_time, 0.362754, 1e-6);
  EXPECT_NEAR(scene.horizon, 2.907, 1e-3);
}

TEST(PushScenes, OutliersAreErrorsFarAboveBothNeighbours) {
  EXPECT_EQ(ps::outliers({1e-3, 1.0, 1e-4}), std::vector<int>{1});
  EXPECT_TRUE(ps::outliers({1e-3, 5e-2, 1e-4}).empty());     // 50x above one neighbour only
  EXPECT_TRUE(ps::outliers({1e-12, 1e-11, 1e-13}).empty());  // round-off is raised to the floor
  EXPECT_TRUE(ps::outliers({1e-3, 1e-6}).empty());           // the ends are not judged
}

}  // namespace
