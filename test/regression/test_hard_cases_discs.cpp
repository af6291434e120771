// Hard case 4: slide around a disc and release from it (hard_cases::DiscRelease: contact at
// polar angle 5 pi / 6, release at the top with lambda -> 0 continuously), against the closed
// form, with FESD on Radau-IIA n_s = 2 at two step sizes.
#include <cmath>

#include <gtest/gtest.h>

#include "support/hard_cases.h"

namespace {

struct ReleaseRun {
  hard_cases::CheckedRun run;
  double grid_error, release_time_error;
};

ReleaseRun simulateRelease(const hard_cases::DiscRelease& problem, int steps) {
  ReleaseRun r{
      hard_cases::simulateTwice(problem.model(), hard_cases::fixedElementCountOptions(2, 2),
                                problem.start(), problem.horizon(), steps, {problem.velocity()}),
      0.0, 0.0};
  const fesd::Trajectory& trajectory = r.run.result.trajectory;
  r.grid_error = hard_cases::maxGridError(trajectory, [&](double t) { return problem.exact(t); });
  if (trajectory.switches.size() == 2u) {
    r.release_time_error = std::fabs(trajectory.switches[1].time - problem.releaseTime());
  }
  return r;
}

TEST(HardCaseDisc, SlidesAroundTheDiscAndReleasesAtTheTop) {
  const hard_cases::DiscRelease problem;
  const ReleaseRun coarse = simulateRelease(problem, 14);  // h0 = 0.125
  const ReleaseRun fine = simulateRelease(problem, 28);
  for (const ReleaseRun* r : {&coarse, &fine}) {
    ASSERT_TRUE(hard_cases::isHealthy(r->run, 1e-9));
    const fesd::Trajectory& trajectory = r->run.result.trajectory;
    ASSERT_EQ(trajectory.switches.size(), 2u);
    EXPECT_EQ(trajectory.switches[0].kind, fesd::SwitchEvent::Kind::kContact);
    EXPECT_EQ(trajectory.switches[1].kind, fesd::SwitchEvent::Kind::kRelease);
    // The contact ends a straight line (integrated exactly), the release a curved slide.
    EXPECT_NEAR(trajectory.switches[0].time, problem.contactTime(), 1e-10);
    // lambda jumps to sqrt(3) / 4 at contact (Prop. 2); lambda = -cos(theta) / 2 on the slide.
    const fesd::ElementValues& slide = trajectory.elements[trajectory.switches[0].element];
    const Eigen::Vector2d p = slide.stage_states.col(0);
    EXPECT_NEAR(slide.stage_multipliers(0, 0), -p(0) / (2.0 * p.norm()), 1e-3);
  }
  // Radau-IIA, n_s = 2: order 2 n_s - 1 = 3 for states and switch times (Nurkanovic et al. 2024,
  // Thm. 17); measured 2.6e-5 -> 2.9e-6 (3.2) and 6.4e-4 -> 3.3e-5 (4.3).
  EXPECT_LT(coarse.grid_error, 5e-5);
  EXPECT_LT(coarse.release_time_error, 1e-3);
  EXPECT_GT(std::log2(coarse.grid_error / fine.grid_error), 2.7);
  EXPECT_GT(std::log2(coarse.release_time_error / fine.release_time_error), 2.7);
  hard_cases::recordNumber("grid_error_h", coarse.grid_error);
  hard_cases::recordNumber("grid_error_h_half", fine.grid_error);
  hard_cases::recordNumber("release_time_error_h", coarse.release_time_error);
  hard_cases::recordNumber("release_time_error_h_half", fine.release_time_error);
}

}  // namespace
