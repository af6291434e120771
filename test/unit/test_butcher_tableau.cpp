// The Butcher tableaus (discretization/butcher_tableau.cpp): Radau-IIA and Gauss-Legendre
// against their closed forms, the order conditions B(p) and C(s), and refused stage counts.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/discretization/butcher_tableau.h"

namespace {

using fesd::CollocationFamily;
using fesd::makeTableau;

TEST(ButcherTableau, RadauIIATwoStagesClosedForm) {
  const auto t = makeTableau(CollocationFamily::kRadauIIA, 2);
  Eigen::Matrix2d a;
  a << 5.0 / 12, -1.0 / 12, 3.0 / 4, 1.0 / 4;
  EXPECT_LT((t.a - a).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((t.b - Eigen::Vector2d(0.75, 0.25)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((t.c - Eigen::Vector2d(1.0 / 3, 1.0)).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(ButcherTableau, RadauIIAThreeStagesClosedForm) {
  const auto t = makeTableau(CollocationFamily::kRadauIIA, 3);
  const double r = std::sqrt(6.0);
  Eigen::Matrix3d a;
  a << (88 - 7 * r) / 360, (296 - 169 * r) / 1800, (-2 + 3 * r) / 225,  //
      (296 + 169 * r) / 1800, (88 + 7 * r) / 360, (-2 - 3 * r) / 225,   //
      (16 - r) / 36, (16 + r) / 36, 1.0 / 9;
  EXPECT_LT((t.a - a).cwiseAbs().maxCoeff(), 2e-15);
  EXPECT_LT((t.c - Eigen::Vector3d((4 - r) / 10, (4 + r) / 10, 1.0)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((t.b - t.a.row(2).transpose()).cwiseAbs().maxCoeff(), 1e-15);
}

TEST(ButcherTableau, ImplicitEulerIsRadauIIAOne) {
  const auto t = makeTableau(CollocationFamily::kRadauIIA, 1);
  EXPECT_DOUBLE_EQ(t.a(0, 0), 1.0);
  EXPECT_DOUBLE_EQ(t.b(0), 1.0);
  EXPECT_DOUBLE_EQ(t.c(0), 1.0);
}

TEST(ButcherTableau, GaussLegendreTwoStagesClosedForm) {
  const auto t = makeTableau(CollocationFamily::kGaussLegendre, 2);
  const double r = std::sqrt(3.0) / 6;
  EXPECT_LT((t.c - Eigen::Vector2d(0.5 - r, 0.5 + r)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_LT((t.b - Eigen::Vector2d(0.5, 0.5)).cwiseAbs().maxCoeff(), 1e-15);
  EXPECT_NEAR(t.a(0, 1), 0.25 - r, 1e-15);
  EXPECT_FALSE(t.lastStageIsEndPoint());
}

/// The simplifying conditions B(p) (quadrature order p) and C(s) (stage order s).
class TableauOrder : public ::testing::TestWithParam<std::pair<CollocationFamily, int>> {};

TEST_P(TableauOrder, SatisfiesQuadratureAndStageOrderConditions) {
  const auto t = makeTableau(GetParam().first, GetParam().second);
  for (int q = 1; q <= t.order(); ++q) {
    EXPECT_NEAR(t.b.dot(t.c.array().pow(q - 1).matrix()), 1.0 / q, 1e-14) << "B(" << q << ")";
  }
  // One degree more must fail (by far more than rounding), or the order is understated.
  const int q = t.order() + 1;
  EXPECT_GT(std::abs(t.b.dot(t.c.array().pow(q - 1).matrix()) - 1.0 / q), 1e-10);
  for (int q = 1; q <= t.stages; ++q) {
    const Eigen::VectorXd lhs = t.a * t.c.array().pow(q - 1).matrix();
    const Eigen::VectorXd rhs = t.c.array().pow(q) / q;
    EXPECT_LT((lhs - rhs).cwiseAbs().maxCoeff(), 1e-14) << "C(" << q << ")";
  }
  EXPECT_EQ(t.lastStageIsEndPoint(), GetParam().first == CollocationFamily::kRadauIIA);
}

INSTANTIATE_TEST_SUITE_P(Schemes, TableauOrder,
                         ::testing::Values(std::make_pair(CollocationFamily::kRadauIIA, 1),
                                           std::make_pair(CollocationFamily::kRadauIIA, 2),
                                           std::make_pair(CollocationFamily::kRadauIIA, 3),
                                           std::make_pair(CollocationFamily::kRadauIIA, 4),
                                           std::make_pair(CollocationFamily::kRadauIIA, 6),
                                           std::make_pair(CollocationFamily::kGaussLegendre, 1),
                                           std::make_pair(CollocationFamily::kGaussLegendre, 3),
                                           std::make_pair(CollocationFamily::kGaussLegendre, 4)));

TEST(ButcherTableau, RejectsUnsupportedStageCounts) {
  EXPECT_THROW(makeTableau(CollocationFamily::kRadauIIA, 0), std::invalid_argument);
  EXPECT_THROW(makeTableau(CollocationFamily::kRadauIIA, 10), std::invalid_argument);
}

}  // namespace
