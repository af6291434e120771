// Trajectory evaluation (discretization/trajectory.cpp): the collocation polynomial and the dense
// path through it, the lowest constraint value along an element's polynomial, and the
// unresolved switches found from it.
#include <cmath>
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

TEST(ClosestApproach, FindsAMinimumBetweenTheSamplesToRounding) {
  // x2(tau) = (tau - 0.55)^2 - 1 touches c = x2 + 1 = 0 at tau = 0.55, between the samples
  // (lowestConstraintBetweenStages sees (0.6 - 0.55)^2 = 2.5e-3 at best).
  const fesd::ButcherTableau radau = fesd::makeTableau(fesd::CollocationFamily::kRadauIIA, 2);
  auto x2 = [](double tau) { return (tau - 0.55) * (tau - 0.55) - 1.0; };
  Eigen::SparseMatrix<double> second(1, 2);
  second.insert(0, 1) = 1.0;
  const fesd::AffineFunction constraint(second, Eigen::VectorXd::Ones(1));
  Eigen::MatrixXd stages(2, 2);
  stages << 0.0, 0.0, x2(radau.c(0)), x2(radau.c(1));
  const Eigen::Vector2d start(0.0, x2(0.0));
  EXPECT_GT(fesd::lowestConstraintBetweenStages(constraint, radau.c, start, stages)(0), 1e-4);
  const fesd::ClosestApproach closest =
      fesd::closestApproach(constraint, 0, radau.c, start, stages);
  EXPECT_NEAR(closest.distance, 0.0, 1e-14);
  EXPECT_NEAR(closest.fraction, 0.55, 1e-6);
}

TEST(DensePath, SamplesEachElementsPolynomialInTimeOrder) {
  // Two Radau-IIA(2) elements of x(tau) = tau^2 (exact for the degree-2 polynomial), each
  // element's tau from 0 to 1 mapped onto [e, e + 1].
  const fesd::ButcherTableau radau = fesd::makeTableau(fesd::CollocationFamily::kRadauIIA, 2);
  fesd::Trajectory trajectory;
  trajectory.stage_nodes = radau.c;
  auto x = [](double t) { return Eigen::VectorXd::Constant(1, t * t); };
  for (int e = 0; e < 2; ++e) {
    trajectory.times.push_back(e);
    trajectory.states.push_back(x(e));
    Eigen::MatrixXd stages(1, 2);
    stages << x(e + radau.c(0)), x(e + radau.c(1));
    trajectory.elements.push_back({0, double(e), 1.0, stages, Eigen::MatrixXd(0, 2),
                                   Eigen::MatrixXd(0, 2), Eigen::VectorXd()});
  }
  trajectory.times.push_back(2.0);
  trajectory.states.push_back(x(2.0));
  EXPECT_NEAR(fesd::collocationState(radau.c, x(1.0), trajectory.elements[1].stage_states, 0.5)(0),
              2.25, 1e-14);
  const std::vector<Eigen::VectorXd> path = fesd::densePath(trajectory, 3);
  // The start, then per element 3 samples and the stage in each of its two gaps.
  ASSERT_EQ(path.size(), 1u + 2 * 2 * (3 + 1));
  double previous = -1.0;
  for (const Eigen::VectorXd& state : path) {
    EXPECT_GT(state(0), previous);  // time order (x increases with t)
    previous = state(0);
  }
  EXPECT_NEAR(path[1](0), std::pow(radau.c(0) / 4.0, 2), 1e-14);  // a quarter into the 1st gap
  EXPECT_NEAR(path.back()(0), 4.0, 1e-14);                        // the last stage is the end
}

}  // namespace
