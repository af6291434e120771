// refinedTrajectory (discretization/refined_trajectory.cpp): a solution moved onto a finer grid
// keeps its element boundaries and reproduces polynomial states and multipliers exactly.
#include <gtest/gtest.h>

#include <algorithm>

#include "fesd_trajopt/discretization/butcher_tableau.h"
#include "fesd_trajopt/discretization/refined_trajectory.h"

namespace {

Eigen::VectorXd state(double t) {
  return Eigen::Vector2d(t * t, 1.0 - 3.0 * t);
}

/// Two intervals of length 1 with elements of lengths {0.4, 0.6} and {0.5, 0.5}, on the
/// polynomial `state` (degree 2: exact for two Radau stages), multiplier lambda(t) = t + 1.
fesd::Trajectory quadraticSolution() {
  const Eigen::VectorXd nodes = fesd::makeTableau(fesd::CollocationFamily::kRadauIIA, 2).c;
  fesd::Trajectory solution;
  solution.stage_nodes = nodes;
  solution.interval_times = {0.0, 1.0, 2.0};
  solution.controls = {Eigen::VectorXd::Constant(1, 0.5), Eigen::VectorXd::Constant(1, -0.5)};
  const double lengths[] = {0.4, 0.6, 0.5, 0.5};
  double t = 0.0;
  solution.times.push_back(t);
  solution.states.push_back(state(t));
  for (int e = 0; e < 4; ++e) {
    fesd::ElementValues element;
    element.interval = e / 2;
    element.start_time = t;
    element.step = lengths[e];
    element.stage_states.resize(2, nodes.size());
    element.stage_multipliers.resize(1, nodes.size());
    element.stage_constraints = Eigen::MatrixXd::Zero(1, nodes.size());
    for (int i = 0; i < nodes.size(); ++i) {
      element.stage_states.col(i) = state(t + nodes(i) * lengths[e]);
      element.stage_multipliers(0, i) = t + nodes(i) * lengths[e] + 1.0;
    }
    solution.elements.push_back(element);
    t += lengths[e];
    solution.times.push_back(t);
    solution.states.push_back(state(t));
  }
  return solution;
}

TEST(RefinedTrajectory, KeepsEveryBoundaryAndTheSolutionsPolynomials) {
  const fesd::Trajectory solution = quadraticSolution();
  EXPECT_EQ(fesd::elementsPerInterval(solution), (std::vector<int>{2, 2}));
  const Eigen::VectorXd nodes = fesd::makeTableau(fesd::CollocationFamily::kRadauIIA, 3).c;
  const fesd::Trajectory refined = fesd::refinedTrajectory(solution, {5, 2}, nodes);
  ASSERT_EQ(refined.elements.size(), 7u);
  EXPECT_EQ(fesd::elementsPerInterval(refined), (std::vector<int>{5, 2}));
  EXPECT_EQ(refined.controls, solution.controls);
  EXPECT_EQ(refined.stage_nodes, nodes);
  for (double boundary : solution.times) {
    EXPECT_NE(std::find(refined.times.begin(), refined.times.end(), boundary), refined.times.end())
        << boundary;
  }
  // 5 = 3 + 2: the longer element (0.6) gets three parts.
  EXPECT_NEAR(refined.elements[0].step, 0.2, 1e-15);
  EXPECT_NEAR(refined.elements[2].step, 0.2, 1e-15);
  EXPECT_NEAR(refined.elements[4].step, 0.2, 1e-15);
  for (size_t e = 0; e < refined.elements.size(); ++e) {
    const fesd::ElementValues& element = refined.elements[e];
    EXPECT_NEAR(refined.times[e], element.start_time, 1e-15);
    EXPECT_NEAR(refined.times[e + 1], element.start_time + element.step, 1e-15);
    EXPECT_LT((refined.states[e + 1] - state(refined.times[e + 1])).norm(), 1e-14);
    for (int i = 0; i < nodes.size(); ++i) {
      const double t = element.start_time + nodes(i) * element.step;
      EXPECT_LT((element.stage_states.col(i) - state(t)).norm(), 1e-14);
      EXPECT_NEAR(element.stage_multipliers(0, i), t + 1.0, 1e-14);
    }
  }
}

TEST(RefinedTrajectory, RefusesFewerElementsOrAWrongCount) {
  const fesd::Trajectory solution = quadraticSolution();
  const Eigen::VectorXd& nodes = solution.stage_nodes;
  EXPECT_THROW(fesd::refinedTrajectory(solution, {1, 2}, nodes), std::invalid_argument);
  EXPECT_THROW(fesd::refinedTrajectory(solution, {2}, nodes), std::invalid_argument);
}

}  // namespace
