// Trajectory evaluation (discretization/trajectory.cpp): the lowest constraint value along an
// element's collocation polynomial, and the unresolved switches found from it.
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/discretization/butcher_tableau.h"
#include "fesd_trajopt/discretization/trajectory.h"
#include "fesd_trajopt/function/affine_function.h"

namespace {

TEST(UnresolvedSwitches, LowestDistanceAlongThePolynomialIsExactForAParabola) {
  // c = x2 + 1 (|grad c| = 1) along x2(tau) = (tau - 0.6)^2 - 1.2 through Radau-IIA(2)'s nodes
  // 1/3 and 1: the lowest point, -0.2 at tau = 0.6, is one of the samples (1/3 + 2/3 * 2/5).
  const fesd::ButcherTableau radau = fesd::makeTableau(fesd::CollocationFamily::kRadauIIA, 2);
  auto x2 = [](double tau) { return (tau - 0.6) * (tau - 0.6) - 1.2; };
  Eigen::SparseMatrix<double> second(1, 2);
  second.insert(0, 1) = 1.0;
  const fesd::AffineFunction constraint(second, Eigen::VectorXd::Ones(1));
  Eigen::MatrixXd stages(2, 2);
  stages << 0.0, 0.0, x2(radau.c(0)), x2(radau.c(1));
  const Eigen::VectorXd lowest = fesd::lowestConstraintBetweenStages(
      constraint, radau.c, Eigen::Vector2d(0.0, x2(0.0)), stages);
  EXPECT_NEAR(lowest(0), -0.2, 1e-12);

  fesd::ElementValues element{
      0,     0.0, 1.0, stages, Eigen::MatrixXd::Zero(1, 2), Eigen::MatrixXd::Constant(1, 2, 0.5),
      lowest};
  const std::vector<fesd::UnresolvedSwitch> found = fesd::findUnresolvedSwitches({element});
  ASSERT_EQ(found.size(), 1u);
  EXPECT_TRUE(found[0].passes_through);
  element.lowest_constraints(0) = -0.01;  // within the tolerance
  EXPECT_TRUE(fesd::findUnresolvedSwitches({element}).empty());
  element.stage_multipliers(0, 1) = 2.0;  // apart at stage 1, in contact at stage 2
  element.stage_constraints(0, 1) = 0.0;
  ASSERT_EQ(fesd::findUnresolvedSwitches({element}).size(), 1u);
  EXPECT_FALSE(fesd::findUnresolvedSwitches({element})[0].passes_through);
  element.stage_constraints(0, 0) = 1e-7;  // weakly active: both sides negligible
  EXPECT_TRUE(fesd::findUnresolvedSwitches({element}).empty());
}

}  // namespace
