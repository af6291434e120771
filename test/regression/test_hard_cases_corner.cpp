// Hard case 1, simultaneous activity: a point driven with constant velocity into the corner of
// two walls that meet at 135 degrees sticks there (co-dimension 2). Both walls are reached at
// the same instant, or one after the other with a slide along the first in between. The motion
// is piecewise linear, so Radau-IIA is exact once the switches sit on element boundaries: every
// error is the solver's and the switch detection's.
#include <cmath>

#include <gtest/gtest.h>

#include "support/hard_cases.h"

namespace {

using hard_cases::isHealthy;
using hard_cases::kCornerVelocity;

/// In the corner u + lambda_1 (0, 1) + lambda_2 (1, 1) / sqrt 2 = 0.
const Eigen::Vector2d kCornerMultipliers(1.0, std::sqrt(2.0));

void expectStuckInCorner(const fesd::Trajectory& trajectory, double arrival) {
  for (const fesd::ElementValues& element : trajectory.elements) {
    if (element.start_time < arrival + 1e-9) continue;
    for (int j = 0; j < element.stage_multipliers.cols(); ++j) {
      EXPECT_NEAR(element.stage_multipliers(0, j), kCornerMultipliers(0), 1e-9);
      EXPECT_NEAR(element.stage_multipliers(1, j), kCornerMultipliers(1), 1e-9);
    }
  }
}

TEST(HardCaseCorner, BothWallsReachedAtOnceStickInTheCorner) {
  // c1 = 2 - 2t and c2 = (3 - 3t) / sqrt 2 vanish together at t = 1, off the nominal grid.
  const Eigen::Vector2d start(1.0, 2.0);
  const auto run =
      hard_cases::simulateTwice(hard_cases::cornerScene(start).model(),
                                hard_cases::fesdOptions(2, 2), start, 2.6, 4, {kCornerVelocity});
  ASSERT_TRUE(isHealthy(run, 1e-9));
  const fesd::Trajectory& trajectory = run.result.trajectory;
  const double error = hard_cases::maxGridError(trajectory, [&](double t) {
    return Eigen::VectorXd(start + std::min(t, 1.0) * kCornerVelocity);
  });
  EXPECT_LT(error, 1e-10);
  ASSERT_EQ(trajectory.switches.size(), 2u);
  for (const fesd::SwitchEvent& event : trajectory.switches) {
    EXPECT_EQ(event.kind, fesd::SwitchEvent::Kind::kContact);
    EXPECT_NEAR(event.time, 1.0, 1e-10);
  }
  expectStuckInCorner(trajectory, 1.0);
  hard_cases::recordNumber("grid_error", error);
}

TEST(HardCaseCorner, SlideAlongTheFloorIntoTheCorner) {
  // Floor reached at t = 0.5 at (1.5, 0), slide with velocity (-1, 0) and lambda_1 = 2 into the
  // corner at t = 2, where lambda_1 drops to 1 (no switch of constraint 0) and lambda_2 jumps.
  const Eigen::Vector2d start(2.0, 1.0);
  const auto run =
      hard_cases::simulateTwice(hard_cases::cornerScene(start).model(),
                                hard_cases::fesdOptions(2, 2), start, 2.9, 4, {kCornerVelocity});
  ASSERT_TRUE(isHealthy(run, 1e-9));
  const fesd::Trajectory& trajectory = run.result.trajectory;
  const double error = hard_cases::maxGridError(trajectory, [&](double t) {
    if (t < 0.5) return Eigen::VectorXd(start + t * kCornerVelocity);
    return Eigen::VectorXd(Eigen::Vector2d(1.5 - std::min(t - 0.5, 1.5), 0.0));
  });
  EXPECT_LT(error, 1e-10);
  const auto floor = hard_cases::switchesOf(trajectory, 0);
  const auto oblique = hard_cases::switchesOf(trajectory, 1);
  ASSERT_EQ(floor.size(), 1u);
  ASSERT_EQ(oblique.size(), 1u);
  EXPECT_NEAR(floor[0].time, 0.5, 1e-10);
  EXPECT_NEAR(oblique[0].time, 2.0, 1e-10);
  for (const fesd::ElementValues& element : trajectory.elements) {
    if (element.start_time < 0.5 - 1e-9 || element.start_time > 2.0 - 1e-9) continue;
    for (int j = 0; j < element.stage_multipliers.cols(); ++j) {
      EXPECT_NEAR(element.stage_multipliers(0, j), 2.0, 1e-9);
    }
  }
  expectStuckInCorner(trajectory, 2.0);
  hard_cases::recordNumber("grid_error", error);
}

}  // namespace
