// Hard case 5, nearly dependent constraints (LICQ almost violated): a point squeezed into a gap
// whose two boundaries have nearly opposite normals, so the contact multipliers grow without
// bound as the gap closes. Both against closed forms.
//  - A V-shaped groove of two walls with normals (+-cos b, sin b), half-opening angle b down to
//    1e-6: from the right wall at height 1 with velocity (1, -1) the point slides down to the
//    apex (piecewise linear: integrated exactly) and sticks with lambda = (1/sin b -+ 1/cos b)/2.
//  - Two overlapping discs of radius rho at (+-d, 0) whose boundaries cross at the nip
//    (0, y*), y* = sqrt(rho^2 - d^2): moving down with velocity (0, -1) the point hits the right
//    disc at polar angle phi_c, slides on it (rho phi' = -cos phi) into the nip and sticks there
//    with lambda_1 = lambda_2 = 1 / (4 y*). See docs/robustness.md for small y*.
#include <cmath>

#include <gtest/gtest.h>

#include "support/hard_cases.h"

namespace {

using hard_cases::isHealthy;

struct Groove {
  double b;
  Eigen::Vector2d start() const { return {std::tan(b), 1.0}; }
  double arrivalTime() const { return 1.0 / (std::cos(b) * (std::cos(b) - std::sin(b))); }
  Eigen::VectorXd exact(double t) const {
    const double s = std::max(1.0 / std::cos(b) - t * (std::cos(b) - std::sin(b)), 0.0);
    return Eigen::Vector2d(s * std::sin(b), s * std::cos(b));
  }
  Eigen::Vector2d apexMultipliers() const {
    return {0.5 * (1.0 / std::sin(b) - 1.0 / std::cos(b)),
            0.5 * (1.0 / std::sin(b) + 1.0 / std::cos(b))};
  }
  std::shared_ptr<const fesd::DcsModel> model() const {
    hard_cases::PointScene point = hard_cases::pointScene(start());
    point.scene.walls().push_back({"left", Eigen::Vector2d(std::cos(b), std::sin(b)), 0.0});
    point.scene.walls().push_back({"right", Eigen::Vector2d(-std::cos(b), std::sin(b)), 0.0});
    return point.model();
  }
};

class HardCaseGroove : public ::testing::TestWithParam<double> {};

TEST_P(HardCaseGroove, SlidesIntoTheApexAndSticksWithLargeMultipliers) {
  const Groove groove{GetParam()};
  const auto run = hard_cases::simulateTwice(groove.model(), hard_cases::fesdOptions(2, 2),
                                             groove.start(), 2.2, 5, {Eigen::Vector2d(1.0, -1.0)});
  ASSERT_TRUE(isHealthy(run, 1e-9));
  const fesd::Trajectory& trajectory = run.result.trajectory;
  const double error =
      hard_cases::maxGridError(trajectory, [&](double t) { return groove.exact(t); });
  // Exact up to Ipopt's tolerance 1e-10, magnified by the conditioning ~ 1 / b of the apex.
  // Measured for b = 1e-2: 1.02e-10 (and multipliers 1.26e-9) under all four BLAS variants,
  // from a polishing solve that ends at Ipopt's tolerance in the stuck phase.
  EXPECT_LT(error, std::max(2e-10, 1e-14 / groove.b));
  const auto left = hard_cases::switchesOf(trajectory, 0);
  ASSERT_EQ(left.size(), 1u);
  EXPECT_EQ(left[0].kind, fesd::SwitchEvent::Kind::kContact);
  EXPECT_NEAR(left[0].time, groove.arrivalTime(), std::max(1e-10, 1e-14 / groove.b));
  EXPECT_TRUE(hard_cases::switchesOf(trajectory, 1).empty());  // on the right wall throughout
  double worst_multiplier_error = 0.0;
  for (const fesd::ElementValues& element : trajectory.elements) {
    if (element.start_time < groove.arrivalTime() - 1e-9) continue;
    for (int j = 0; j < element.stage_multipliers.cols(); ++j) {
      const Eigen::Vector2d relative =
          element.stage_multipliers.col(j).cwiseQuotient(groove.apexMultipliers()) -
          Eigen::Vector2d::Ones();
      worst_multiplier_error = std::max(worst_multiplier_error, relative.cwiseAbs().maxCoeff());
    }
  }
  EXPECT_LT(worst_multiplier_error, std::max(2e-9, 1e-12 / groove.b));
  hard_cases::recordNumber("grid_error", error);
  hard_cases::recordNumber("relative_multiplier_error", worst_multiplier_error);
}

INSTANTIATE_TEST_SUITE_P(OpeningAngles, HardCaseGroove, ::testing::Values(0.3, 1e-2, 1e-4, 1e-6));

struct Nip {
  double rho, y_star, start_x;
  double d() const { return std::sqrt(rho * rho - y_star * y_star); }
  double height() const { return 2.0 * rho; }
  /// An antiderivative of sec on (pi / 2, pi).
  static double g(double phi) { return std::log((1.0 + std::sin(phi)) / -std::cos(phi)); }
  double contactAngle() const { return std::acos((start_x - d()) / rho); }
  double nipAngle() const { return std::acos(-d() / rho); }
  double contactTime() const { return height() - rho * std::sin(contactAngle()); }
  double arrivalTime() const { return contactTime() + rho * (g(contactAngle()) - g(nipAngle())); }
  Eigen::VectorXd exact(double t) const {
    if (t <= contactTime()) return Eigen::Vector2d(start_x, height() - t);
    if (t >= arrivalTime()) return Eigen::Vector2d(0.0, y_star);
    const double phi =
        1.5 * M_PI - 2.0 * std::atan(std::exp(g(contactAngle()) - (t - contactTime()) / rho));
    return Eigen::Vector2d(d() + rho * std::cos(phi), rho * std::sin(phi));
  }
  std::shared_ptr<const fesd::DcsModel> model() const {
    hard_cases::PointScene point = hard_cases::pointScene(Eigen::Vector2d::Zero());
    point.scene.obstacles().push_back({"left", rho, Eigen::Vector2d(-d(), 0.0)});
    point.scene.obstacles().push_back({"right", rho, Eigen::Vector2d(d(), 0.0)});
    return point.model();
  }
};

class HardCaseNip : public ::testing::TestWithParam<double> {};

TEST_P(HardCaseNip, SlidesIntoTheNipAndSticks) {
  const Nip nip{1.5, GetParam(), 0.3};
  const Eigen::Vector2d start(nip.start_x, nip.height());
  const double horizon = 4.0;
  const auto run = hard_cases::simulateTwice(nip.model(), hard_cases::fesdOptions(2, 2), start,
                                             horizon, 20, {Eigen::Vector2d(0.0, -1.0)});
  ASSERT_TRUE(isHealthy(run, 1e-9));
  const fesd::Trajectory& trajectory = run.result.trajectory;
  const double error = hard_cases::maxGridError(trajectory, [&](double t) { return nip.exact(t); });
  const auto left = hard_cases::switchesOf(trajectory, 0);
  const auto right = hard_cases::switchesOf(trajectory, 1);
  ASSERT_EQ(left.size(), 1u);
  ASSERT_EQ(right.size(), 1u);
  EXPECT_NEAR(right[0].time, nip.contactTime(), 1e-10);
  // The arrival ends a curved slide: an O(h^3) error like the states'.
  const double arrival_error = std::fabs(left[0].time - nip.arrivalTime());
  EXPECT_LT(arrival_error, 1e-5);
  EXPECT_LT(error, 1e-5);
  // Stuck in the nip: exactly there, with the multipliers of the limit.
  EXPECT_LT((trajectory.finalState() - nip.exact(horizon)).norm(), 1e-10);
  const fesd::ElementValues& last = trajectory.elements.back();
  for (int k = 0; k < 2; ++k) {
    EXPECT_NEAR(last.stage_multipliers(k, 0) * 4.0 * nip.y_star, 1.0, 1e-9);
  }
  hard_cases::recordNumber("grid_error", error);
  hard_cases::recordNumber("arrival_time_error", arrival_error);
}

INSTANTIATE_TEST_SUITE_P(Gaps, HardCaseNip, ::testing::Values(0.5, 0.2));

}  // namespace
