// Push-T in our units (examples/push_t.cpp): the T's shape (bar 4 w by w, stem w by 3 w, 12
// spheres), its centre of pressure as its position, the target pose, and the random starts
// (within half the table, the pusher clear of the T, valid tasks).
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/push_t.h"
#include "fesd_trajopt/scene/limit_surface.h"

namespace {

TEST(PushT, TheTIsABarOverAStemTurningAboutItsCentreOfPressure) {
  const double w = 0.5;
  const fesd::SceneBody t = fesd::push_t::tBlock(Eigen::Vector2d(1.0, 2.0), 0.0, w);
  ASSERT_EQ(t.spheres.size(), 12u);
  EXPECT_TRUE(t.turns);
  EXPECT_EQ(t.position, Eigen::Vector2d(1.0, 2.0));
  // Equal spheres: the centre of pressure is their mean, 7 on the bar at y = 0 and 5 on the stem
  // at y = -w .. -3 w (mean -2 w): -10 w / 12 below the bar's centre line.
  const double below = 10.0 * w / 12.0;
  Eigen::Vector2d low(1e9, 1e9), high(-1e9, -1e9);
  for (const fesd::FreeBodySphere& sphere : t.spheres) {
    EXPECT_EQ(sphere.radius, 0.5 * w);
    low = low.cwiseMin(sphere.offset.head<2>() - Eigen::Vector2d::Constant(0.5 * w));
    high = high.cwiseMax(sphere.offset.head<2>() + Eigen::Vector2d::Constant(0.5 * w));
  }
  // Its extent: 4 w wide; from the bar's top (w / 2 above its centre line) to the stem's end
  // (3.5 w below it).
  EXPECT_NEAR(high.x() - low.x(), 4.0 * w, 1e-12);
  EXPECT_NEAR(high.y() - low.y(), 4.0 * w, 1e-12);
  EXPECT_NEAR(high.y(), 0.5 * w + below, 1e-12);
  EXPECT_LT(fesd::pressureCentre(fesd::footprintOf(t)).norm(), 1e-12);
  EXPECT_EQ(fesd::turningBodyProblem(t), "");
}

TEST(PushT, RandomStartsAreValidTasksToTheTargetPoseWithinHalfATurn) {
  for (unsigned seed = 0; seed < 16; ++seed) {
    const fesd::SceneTask task = fesd::push_t::randomStart(seed);
    EXPECT_EQ(fesd::validateTask(task, fesd::TaskLimits{}), "") << seed;
    EXPECT_EQ(fesd::infeasibility(task), "") << seed;
    const fesd::SceneBody& t = task.scene.bodies()[1];
    EXPECT_LE(t.position.norm(), 2.5) << seed;
    const double turn = task.bodies[1].target_yaw - t.yaw;
    EXPECT_LE(std::fabs(turn), M_PI + 1e-12) << seed;
    EXPECT_NEAR(std::remainder(task.bodies[1].target_yaw - fesd::push_t::targetYaw(), 2 * M_PI),
                0.0, 1e-12)
        << seed;
    EXPECT_EQ(task.bodies[1].target, fesd::push_t::targetPosition());
  }
}

}  // namespace
