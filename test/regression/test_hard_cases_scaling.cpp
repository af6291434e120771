// Hard case 7, scaling extremes, on the disc release of case 4 (hard_cases::DiscRelease) and the
// corner of case 1:
//  - lengths R from 1e-3 to 1e3 and horizons from 0.1 to 100: the scaled problem is the unit one
//    in other units, so the relative errors must stay those of the unit problem;
//  - tight and loose step bounds gamma_h: a switch is found only where an element boundary can
//    reach it, otherwise the step must fail and say so;
//  - n_s = 1..4.
#include <cmath>

#include <gtest/gtest.h>

#include "support/hard_cases.h"

namespace {

using hard_cases::isHealthy;

constexpr int kSteps = 14;

struct RelativeErrors {
  double state, contact_time;
};

RelativeErrors relativeErrors(const hard_cases::DiscRelease& problem,
                              const fesd::SimulationResult& result) {
  const fesd::Trajectory& trajectory = result.trajectory;
  const double time_unit = problem.radius / problem.speed;
  return {hard_cases::maxGridError(trajectory, [&](double t) { return problem.exact(t); }) /
              problem.radius,
          trajectory.switches.empty()
              ? INFINITY
              : std::fabs(trajectory.switches[0].time - problem.contactTime()) / time_unit};
}

double unitScaleError() {
  const hard_cases::DiscRelease unit;
  fesd::FesdIntegrator integrator(unit.model(), hard_cases::fesdOptions(2, 2));
  const fesd::SimulationResult result =
      integrator.simulate(unit.start(), unit.horizon(), kSteps, {unit.velocity()});
  EXPECT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  return relativeErrors(unit, result).state;
}

/// (radius, speed): horizon 3.5 R / v.
class HardCaseScaling : public ::testing::TestWithParam<std::pair<double, double>> {};

TEST_P(HardCaseScaling, RelativeErrorsMatchTheUnitScale) {
  const hard_cases::DiscRelease problem{GetParam().first, GetParam().second};
  fesd::SimulationOptions options = hard_cases::fesdOptions(2, 2);
  // The pass-through depth is a length: it scales with the scene (at R = 1e3 the default 3e-2
  // flags the resolved slide, whose polynomial bends off the disc by R times the unit's).
  options.penetration_tolerance *= problem.radius;
  const auto run = hard_cases::simulateTwice(problem.model(), options, problem.start(),
                                             problem.horizon(), kSteps, {problem.velocity()});
  ASSERT_TRUE(isHealthy(run, 1e-9));
  ASSERT_EQ(run.result.trajectory.switches.size(), 2u);
  const RelativeErrors errors = relativeErrors(problem, run.result);
  static const double unit = unitScaleError();  // 2.0e-5
  // Measured 0.95 to 1.85 times the unit-scale error (different rounding, homotopy paths).
  EXPECT_LT(errors.state, 2.5 * unit);
  // Measured 2e-15 to 2e-11, but 1.7e-7 for R = 1e-3, T = 0.1 (absolute tolerances, see below).
  EXPECT_LT(errors.contact_time, 1e-6);
  hard_cases::recordNumber("horizon", problem.horizon());
  hard_cases::recordNumber("relative_state_error", errors.state);
  hard_cases::recordNumber("unit_scale_error", unit);
  hard_cases::recordNumber("relative_contact_time_error", errors.contact_time);
  hard_cases::recordNumber("ipopt_iterations", run.result.totals.iterations);
}

INSTANTIATE_TEST_SUITE_P(LengthsAndHorizons, HardCaseScaling,
                         ::testing::Values(std::make_pair(1e-3, 1e-2),    // T = 0.35
                                           std::make_pair(1e-3, 3.5e-2),  // T = 0.1
                                           std::make_pair(1e3, 1e2),      // T = 35
                                           std::make_pair(1e3, 35.0)));   // T = 100

TEST(HardCaseScaling, SmallSlowSceneKeepsTheUnitScaleAccuracy) {
  // R = 1e-3 at speed 1e-3 (T = 3.5): c = |p|^2 - R^2 is ~1e-6 while lambda ~ v/R = 1. Comparing
  // c with lambda directly made polishing fix contacts that were not there (relative error
  // 1.05e-3, 40 x the unit scale); compared in one unit (c / |grad c| against h0 lambda
  // |grad c|, DcsModel::constraintScales) it keeps the unit problem's accuracy: measured 1.7e-5
  // to 2.0e-5 (by BLAS).
  const hard_cases::DiscRelease problem{1e-3, 1e-3};
  const auto run =
      hard_cases::simulateTwice(problem.model(), hard_cases::fesdOptions(2, 2), problem.start(),
                                problem.horizon(), kSteps, {problem.velocity()});
  ASSERT_TRUE(isHealthy(run, 1e-9));
  const RelativeErrors errors = relativeErrors(problem, run.result);
  static const double unit = unitScaleError();
  EXPECT_LT(errors.state, 2.5 * unit);
  EXPECT_LT(errors.contact_time, 1e-6);
  hard_cases::recordNumber("relative_state_error", errors.state);
  hard_cases::recordNumber("relative_contact_time_error", errors.contact_time);
}

TEST(HardCaseScaling, StageCountsOneToFour) {
  // Errors at h0 = 0.125 measured 4.1e-2, 2.0e-5, 1.0e-8, 3.4e-13 (order 2 n_s - 1 per stage
  // count; the switch steps refined, SimulationOptions::refine_elements); the bounds are 2-3 times
  // the measurements, n_s = 4's at the round-off plateau of the polished steps.
  const double bounds[] = {1e-1, 5e-5, 3e-8, 5e-11};
  const hard_cases::DiscRelease problem;
  for (int stages = 1; stages <= 4; ++stages) {
    const auto run =
        hard_cases::simulateTwice(problem.model(), hard_cases::fesdOptions(stages, 2),
                                  problem.start(), problem.horizon(), kSteps, {problem.velocity()});
    ASSERT_TRUE(isHealthy(run, 1e-9)) << "n_s = " << stages;
    const double error = relativeErrors(problem, run.result).state;
    EXPECT_LT(error, bounds[stages - 1]) << "n_s = " << stages;
    hard_cases::recordNumber("error_ns" + std::to_string(stages), error);
  }
}

TEST(HardCaseScaling, StepBoundsTightAndLoose) {
  // Corner of case 1: contact with both walls at t = 1; 4 steps, 2 elements each, so the only
  // movable boundary of a step lies within (1 -+ gamma_h) h0 of its start.
  const Eigen::Vector2d start(1.0, 2.0);
  const auto model = hard_cases::cornerScene(start).model();
  const auto exact = [&](double t) {
    return Eigen::VectorXd(start + std::min(t, 1.0) * hard_cases::kCornerVelocity);
  };
  // T = 2.6: t = 1 is 0.35 into the second step of 0.65, i.e. at 1.077 h0: reachable even
  // with gamma_h = 0.1.
  for (double gamma : {0.1, 0.5, 1.0}) {
    const auto run = hard_cases::simulateTwice(model, hard_cases::fesdOptions(2, 2, gamma), start,
                                               2.6, 4, {hard_cases::kCornerVelocity});
    ASSERT_TRUE(isHealthy(run, 1e-9)) << "gamma_h = " << gamma;
    EXPECT_LT(hard_cases::maxGridError(run.result.trajectory, exact), 1e-10);
    ASSERT_EQ(run.result.trajectory.switches.size(), 2u);
    EXPECT_NEAR(run.result.trajectory.switches[0].time, 1.0, 1e-10);
  }
  // T = 2.9: t = 1 is 0.275 into the second step of 0.725, at 0.76 h0: out of reach for
  // gamma_h = 0.1. The step cannot be solved as one: without splitting the integrator stops
  // there and reports it; by default it solves the step in halves, where t = 1 is reachable.
  fesd::SimulationOptions unsplit = hard_cases::fesdOptions(2, 2, 0.1);
  unsplit.max_step_splits = 0;
  const auto tight =
      hard_cases::simulateTwice(model, unsplit, start, 2.9, 4, {hard_cases::kCornerVelocity});
  EXPECT_TRUE(tight.identical);
  EXPECT_NE(tight.result.status, fesd::SolveStatus::kSuccess);
  EXPECT_EQ(tight.result.completed_steps, 1);
  EXPECT_NE(tight.result.message.find("step 1 of 4"), std::string::npos) << tight.result.message;
  const auto split = hard_cases::simulateTwice(model, hard_cases::fesdOptions(2, 2, 0.1), start,
                                               2.9, 4, {hard_cases::kCornerVelocity});
  ASSERT_TRUE(isHealthy(split, 1e-9));
  EXPECT_EQ(split.result.split_steps, 1);
  EXPECT_LT(hard_cases::maxGridError(split.result.trajectory, exact), 1e-10);
  EXPECT_NEAR(split.result.trajectory.switches.at(0).time, 1.0, 1e-10);
  const auto loose = hard_cases::simulateTwice(model, hard_cases::fesdOptions(2, 2, 1.0), start,
                                               2.9, 4, {hard_cases::kCornerVelocity});
  ASSERT_TRUE(isHealthy(loose, 1e-9));
  EXPECT_LT(hard_cases::maxGridError(loose.result.trajectory, exact), 1e-10);
}

}  // namespace
