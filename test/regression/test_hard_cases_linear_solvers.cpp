// The hard cases under both KKT solves behind Ipopt: our LDL^T (the default) against MUMPS (the
// reference). Every step goes through the homotopy (no active-set Newton), so every number
// below comes out of Ipopt's linear solves; our residuals must be no worse than MUMPS's and the
// trajectories the same up to the solver tolerance.
#include <cmath>
#include <cstdio>
#include <string>

#include <gtest/gtest.h>

#include "support/hard_cases.h"

namespace {

struct HardCase {
  std::string name;
  std::shared_ptr<const fesd::DcsModel> model;
  Eigen::VectorXd start, control;
  double horizon, length_scale;
  int steps;
};

std::vector<HardCase> hardCases() {
  std::vector<HardCase> cases;
  for (const Eigen::Vector2d& start : {Eigen::Vector2d(1.0, 2.0), Eigen::Vector2d(2.0, 1.0)}) {
    cases.push_back({"corner", hard_cases::cornerScene(start).model(), start,
                     hard_cases::kCornerVelocity, 2.9, 1.0, 4});
  }
  // The disc release at unit scale and at the scaling extremes of hard case 7.
  for (const auto& [radius, speed] : {std::pair{1.0, 1.0}, {1e-3, 1e-3}, {1e3, 1e2}}) {
    const hard_cases::DiscRelease problem{radius, speed};
    char name[32];
    std::snprintf(name, sizeof name, "disc_release_R%g", radius);
    cases.push_back({name, problem.model(), problem.start(), problem.velocity(), problem.horizon(),
                     radius, 14});
  }
  return cases;
}

hard_cases::CheckedRun simulateWith(const HardCase& c, const std::string& linear_solver) {
  fesd::SimulationOptions options = hard_cases::fesdOptions(2, 2);
  options.active_set_steps = false;
  options.penetration_tolerance *= c.length_scale;
  options.homotopy.ipopt.linear_solver = linear_solver;
  options.retry_homotopy.ipopt.linear_solver = linear_solver;
  return hard_cases::simulateTwice(c.model, options, c.start, c.horizon, c.steps, {c.control});
}

TEST(HardCasesUnderBothKktSolves, OurResidualsAreNoWorseThanMumps) {
  for (const HardCase& c : hardCases()) {
    SCOPED_TRACE(c.name);
    const hard_cases::CheckedRun ours = simulateWith(c, fesd::kLdltSolver);
    const hard_cases::CheckedRun mumps = simulateWith(c, "mumps");
    ASSERT_TRUE(hard_cases::isHealthy(ours, 1e-9));
    ASSERT_TRUE(hard_cases::isHealthy(mumps, 1e-9));
    const double our_residual = ours.result.totals.complementarity_residual;
    const double mumps_residual = mumps.result.totals.complementarity_residual;
    // "No worse" up to rounding: both end at Ipopt's tolerance 1e-10 on their last relaxation.
    EXPECT_LE(our_residual, std::max(2.0 * mumps_residual, 1e-12))
        << "ours " << our_residual << ", MUMPS " << mumps_residual;
    const fesd::Trajectory& a = ours.result.trajectory;
    const fesd::Trajectory& b = mumps.result.trajectory;
    ASSERT_EQ(a.switches.size(), b.switches.size());
    for (size_t k = 0; k < a.switches.size(); ++k) {
      EXPECT_NEAR(a.switches[k].time, b.switches[k].time, 1e-8 * c.horizon);
    }
    // The same end state up to the discretisation error (2e-5 R against the exact motion, hard
    // case 7): at R = 1e-3 the two homotopies take different paths (measured 8e-6 R apart).
    EXPECT_LT(
        (a.elements.back().stage_states.rightCols(1) - b.elements.back().stage_states.rightCols(1))
            .norm(),
        1e-5 * c.length_scale);
    hard_cases::recordNumber(c.name + "_residual_ours", our_residual);
    hard_cases::recordNumber(c.name + "_residual_mumps", mumps_residual);
    std::printf("%s residual ours %.3g mumps %.3g iterations ours %d mumps %d\n", c.name.c_str(),
                our_residual, mumps_residual, ours.result.totals.iterations,
                mumps.result.totals.iterations);
  }
}

}  // namespace
