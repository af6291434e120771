// Hard cases 2 and 3 on the floor x2 >= 0 with xdot = (1, x1 + a) + (0, lambda): a parabola
// x2 = x2(0) + a t + (x1(0) t + t^2 / 2). Radau-IIA with n_s = 2 integrates the quadratic
// free motion, the slide (lambda = -(x1 + a), linear) and the switch-free pieces exactly, so
// every error below is the solver's and the switch detection's, not the method's.
//  - Case 2, grazing: from (-1, 1/2 + eps) with a = 0 the free parabola touches the floor
//    tangentially at t = 1 when eps = 0 (lambda stays 0); eps > 0 passes above it, eps < 0
//    slides on it from 1 - sqrt(-2 eps) to the release at t = 1. For t >= 1 all three coincide
//    up to max(eps, 0).
//  - Case 3, starting on the floor: with lambda > 0 (sliding, a = -1: release at t = 1), and
//    with lambda = 0, leaving it tangentially (a = 0) or transversally (f = (1, 1)).
#include <cmath>

#include <gtest/gtest.h>

#include "support/hard_cases.h"

namespace {

using hard_cases::isHealthy;

/// xdot = (1, x1 + a) + (0, lambda), 0 <= x2 _|_ lambda >= 0.
std::shared_ptr<const fesd::DcsModel> parabolaModel(double a) {
  Eigen::Matrix2d F;
  F << 0.0, 0.0, 1.0, 0.0;
  return hard_cases::affineModel(F, Eigen::Vector2d(1.0, a), Eigen::RowVector2d(0.0, 1.0),
                                 Eigen::VectorXd::Zero(1));
}

constexpr double kHorizon = 2.3;  // 10 steps of 0.23: t = 1 lies inside a step
constexpr int kSteps = 10;

/// Four elements per step: a short slide needs its contact and its release in one step.
fesd::SimulationOptions boundaryOptions(int elements = 4) {
  return hard_cases::fesdOptions(2, elements);
}

Eigen::VectorXd grazingExact(double eps, double t) {
  const double x1 = -1.0 + t, free = eps + 0.5 * (t - 1.0) * (t - 1.0);
  if (eps >= 0.0) return Eigen::Vector2d(x1, free);
  const double contact = 1.0 - std::sqrt(-2.0 * eps);
  return Eigen::Vector2d(x1, t < contact ? free : t < 1.0 ? 0.0 : free - eps);
}

struct GrazingRun {
  hard_cases::CheckedRun run;
  double error;  ///< largest state error on the grid
};

GrazingRun simulateGrazing(double eps, int elements = 4) {
  GrazingRun g{hard_cases::simulateTwice(parabolaModel(0.0), boundaryOptions(elements),
                                         Eigen::Vector2d(-1.0, 0.5 + eps), kHorizon, kSteps),
               0.0};
  g.error = hard_cases::maxGridError(g.run.result.trajectory,
                                     [&](double t) { return grazingExact(eps, t); });
  return g;
}

class HardCaseGrazing : public ::testing::TestWithParam<double> {};

TEST_P(HardCaseGrazing, MatchesTheExactSolutionOnEitherSide) {
  const double eps = GetParam();
  const GrazingRun g = simulateGrazing(eps);
  ASSERT_TRUE(isHealthy(g.run, 1e-9));
  const fesd::Trajectory& trajectory = g.run.result.trajectory;
  EXPECT_LT(g.error, 1e-10);
  const double largest_multiplier = hard_cases::maxMultiplier(trajectory, 0);
  if (eps >= 0.0) {
    EXPECT_TRUE(trajectory.switches.empty());
    EXPECT_LT(largest_multiplier, 1e-10);  // lambda stays (continuously) zero
  } else {
    const double contact = 1.0 - std::sqrt(-2.0 * eps);
    ASSERT_EQ(trajectory.switches.size(), 2u);
    EXPECT_EQ(trajectory.switches[0].kind, fesd::SwitchEvent::Kind::kContact);
    EXPECT_NEAR(trajectory.switches[0].time, contact, 1e-10);
    EXPECT_EQ(trajectory.switches[1].kind, fesd::SwitchEvent::Kind::kRelease);
    EXPECT_NEAR(trajectory.switches[1].time, 1.0, 1e-10);
    // On the slide lambda = 1 - t = -x1 at every stage point.
    int sliding_stages = 0;
    for (const fesd::ElementValues& element : trajectory.elements) {
      for (int j = 0; j < element.stage_multipliers.cols(); ++j) {
        if (element.stage_multipliers(0, j) < 1e-9) continue;
        ++sliding_stages;
        EXPECT_NEAR(element.stage_multipliers(0, j), -element.stage_states(0, j), 1e-10);
      }
    }
    EXPECT_GT(sliding_stages, 0);
    EXPECT_LT(largest_multiplier, 1.0 - contact);
  }
  hard_cases::recordNumber("grid_error", g.error);
}

INSTANTIATE_TEST_SUITE_P(Perturbations, HardCaseGrazing,
                         ::testing::Values(0.0, 1e-9, 1e-6, 1e-3, -1e-3, -1e-2));

/// A dip shorter than the stage spacing: c >= 0 is imposed at the stage points only, and the
/// free parabola's dip below the floor, 2 sqrt(-2 eps) long, falls between two of them. FESD
/// then finds no contact; the state error is the missed penetration depth -eps.
class HardCaseShallowDip : public ::testing::TestWithParam<double> {};

TEST(HardCaseShallowDipResolved, ADipOfDepth1e4IsFoundWhenTheStepIsSplit) {
  // 2 sqrt(2e-4) = 0.028 long: the step holding it has no polishable active set, so it is solved
  // in parts (SimulationOptions::max_step_splits), whose stage points catch the contact.
  const double eps = -1e-4;
  const GrazingRun g = simulateGrazing(eps);
  ASSERT_TRUE(isHealthy(g.run, 1e-9));
  const fesd::Trajectory& trajectory = g.run.result.trajectory;
  EXPECT_GE(g.run.result.split_steps, 1);
  ASSERT_EQ(trajectory.switches.size(), 2u);
  // The contact is nearly tangential (the height falls at 2 sqrt(-2 eps) = 0.028 there), so a
  // state error of 1e-10 moves it by some 1e-8 (measured 7.5e-9).
  EXPECT_NEAR(trajectory.switches[0].time, 1.0 - std::sqrt(-2.0 * eps), 5e-8);
  EXPECT_NEAR(trajectory.switches[1].time, 1.0, 5e-8);
  EXPECT_LT(g.error, 1e-9);  // measured 1.05e-10 under all BLAS variants
  hard_cases::recordNumber("grid_error", g.error);
}

TEST_P(HardCaseShallowDip, IsMissedWithAnErrorOfItsDepth) {
  const double eps = GetParam();
  const GrazingRun g = simulateGrazing(eps);
  ASSERT_TRUE(isHealthy(g.run, 1e-9));
  const fesd::Trajectory& trajectory = g.run.result.trajectory;
  EXPECT_TRUE(trajectory.switches.empty());
  EXPECT_NEAR(g.error, -eps, 1e-3 * -eps + 1e-10);
  hard_cases::recordNumber("grid_error", g.error);
}

INSTANTIATE_TEST_SUITE_P(Depths, HardCaseShallowDip, ::testing::Values(-1e-6, -1e-9));

TEST(HardCaseGrazingContract, ShortSlideIsSolvedOrReportedAsFailed) {
  // With three elements per step the homotopy ends in a wrong active set (contact in the element
  // that starts the step, off the boundary). Polishing used to fix the smaller side of a pair
  // even when that side held nonzero data (the start point's c), and reported success with a
  // complementarity residual of 7e-6. Success must mean what it says.
  const double eps = -1e-3;
  const GrazingRun g = simulateGrazing(eps, 3);
  const fesd::SimulationResult& result = g.run.result;
  EXPECT_TRUE(g.run.identical);
  ::testing::Test::RecordProperty("solve_status", fesd::statusName(result.status));
  hard_cases::recordNumber("complementarity_residual", result.totals.complementarity_residual);
  if (result.status == fesd::SolveStatus::kSuccess) {
    EXPECT_LE(result.totals.complementarity_residual, 1e-9);
    EXPECT_LT(g.error, 1e-10);
  } else {
    EXPECT_GT(result.totals.complementarity_residual, 1e-9) << result.message;
  }
}

TEST(HardCaseStartOnBoundary, SlidingWithPositiveMultiplierUntilRelease) {
  // From (0, 0) with a = -1: lambda = 1 - t > 0 from the start, release at t = 1 where lambda
  // reaches 0 continuously, then x2 = (t - 1)^2 / 2.
  const auto run = hard_cases::simulateTwice(parabolaModel(-1.0), boundaryOptions(),
                                             Eigen::Vector2d::Zero(), kHorizon, kSteps);
  ASSERT_TRUE(isHealthy(run, 1e-9));
  const fesd::Trajectory& trajectory = run.result.trajectory;
  const double error = hard_cases::maxGridError(trajectory, [](double t) {
    return Eigen::VectorXd(Eigen::Vector2d(t, t < 1.0 ? 0.0 : 0.5 * (t - 1.0) * (t - 1.0)));
  });
  EXPECT_LT(error, 1e-10);
  ASSERT_EQ(trajectory.switches.size(), 1u);  // active from the start: no contact event
  EXPECT_EQ(trajectory.switches[0].kind, fesd::SwitchEvent::Kind::kRelease);
  EXPECT_NEAR(trajectory.switches[0].time, 1.0, 1e-10);
  const fesd::ElementValues& first = trajectory.elements.front();
  EXPECT_NEAR(first.stage_multipliers(0, 0), 1.0 - first.stage_states(0, 0), 1e-10);
  hard_cases::recordNumber("grid_error", error);
}

/// From the origin on the floor with lambda = 0: the constraint is released at t = 0.
void expectLeavesAtOnce(const hard_cases::CheckedRun& run,
                        const std::function<double(double)>& height) {
  ASSERT_TRUE(isHealthy(run, 1e-9));
  const fesd::Trajectory& trajectory = run.result.trajectory;
  const double error = hard_cases::maxGridError(
      trajectory, [&](double t) { return Eigen::VectorXd(Eigen::Vector2d(t, height(t))); });
  EXPECT_LT(error, 1e-10);
  EXPECT_LT(hard_cases::maxMultiplier(trajectory, 0), 1e-10);
  ASSERT_EQ(trajectory.switches.size(), 1u);
  EXPECT_EQ(trajectory.switches[0].kind, fesd::SwitchEvent::Kind::kRelease);
  EXPECT_EQ(trajectory.switches[0].time, 0.0);
}

TEST(HardCaseStartOnBoundary, LeavingTangentiallyWithZeroMultiplier) {
  expectLeavesAtOnce(hard_cases::simulateTwice(parabolaModel(0.0), boundaryOptions(),
                                               Eigen::Vector2d::Zero(), kHorizon, kSteps),
                     [](double t) { return 0.5 * t * t; });
}

TEST(HardCaseStartOnBoundary, LeavingTransversallyWithZeroMultiplier) {
  const auto model =
      hard_cases::affineModel(Eigen::Matrix2d::Zero(), Eigen::Vector2d(1.0, 1.0),
                              Eigen::RowVector2d(0.0, 1.0), Eigen::VectorXd::Zero(1));
  expectLeavesAtOnce(hard_cases::simulateTwice(model, boundaryOptions(), Eigen::Vector2d::Zero(),
                                               kHorizon, kSteps),
                     [](double t) { return t; });
}

}  // namespace
