// The examples of Nurkanovic et al. 2024 with Stewart's reformulation: integration orders of
// example (47), the optimum of OCP (56) from several guesses, and OCP (61) with two sliding
// surfaces.
#include <cmath>
#include <set>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/discretization/stewart_discretization.h"
#include "fesd_trajopt/examples/filippov_examples.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/ocp/ocp_solver.h"

namespace {

using fesd::CollocationFamily;

/// Least-squares slope of log(error) over log(h).
double fittedOrder(const std::vector<double>& steps, const std::vector<double>& errors) {
  const int n = static_cast<int>(steps.size());
  double mean_x = 0.0, mean_y = 0.0;
  for (int i = 0; i < n; ++i) {
    mean_x += std::log(steps[i]) / n;
    mean_y += std::log(errors[i]) / n;
  }
  double covariance = 0.0, variance = 0.0;
  for (int i = 0; i < n; ++i) {
    covariance += (std::log(steps[i]) - mean_x) * (std::log(errors[i]) - mean_y);
    variance += std::pow(std::log(steps[i]) - mean_x, 2);
  }
  return covariance / variance;
}

struct OrderCase {
  CollocationFamily family;
  int stages;
  bool fesd;
  std::vector<int> totals;  ///< finite elements on [0, T], in the asymptotic range
  int elements_per_step;
};

/// The fitted order of example (47)'s terminal error, every simulation converged.
double spiralOrder(const OrderCase& c) {
  namespace example = fesd::spiral_example;
  std::vector<double> steps, errors;
  for (int total : c.totals) {
    fesd::SimulationOptions options;
    options.discretization.family = c.family;
    options.discretization.num_stages = c.stages;
    options.discretization.num_elements = c.elements_per_step;
    options.discretization.switch_detection = c.fesd;
    fesd::FesdIntegrator integrator(example::model(), options);
    const fesd::SimulationResult result = integrator.simulate(
        example::initialState(), example::horizon(), total / c.elements_per_step);
    EXPECT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
    steps.push_back(example::horizon() / total);
    errors.push_back(
        (result.trajectory.finalState() - example::exactState(example::horizon())).norm());
  }
  return fittedOrder(steps, errors);
}

class SpiralFesdOrder : public ::testing::TestWithParam<OrderCase> {};

/// Nurkanovic et al. 2024 Sec. 4.4: FESD recovers the order the scheme has on smooth ODE: 2 n_s - 1
/// for Radau-IIA, 2 n_s for Gauss-Legendre.
TEST_P(SpiralFesdOrder, MatchesTheSchemesSmoothOrder) {
  const OrderCase& c = GetParam();
  const int expected = fesd::makeTableau(c.family, c.stages).order();
  EXPECT_NEAR(spiralOrder(c), expected, 0.3);
}

INSTANTIATE_TEST_SUITE_P(
    Schemes, SpiralFesdOrder,
    // Implicit Euler damps the spiral (|w h| must be small): only h <= 0.006 is asymptotic.
    ::testing::Values(OrderCase{CollocationFamily::kRadauIIA, 1, true, {256, 512, 1024}, 32},
                      OrderCase{CollocationFamily::kRadauIIA, 2, true, {32, 48, 64}, 2},
                      OrderCase{CollocationFamily::kRadauIIA, 3, true, {16, 24, 32}, 2},
                      OrderCase{CollocationFamily::kGaussLegendre, 1, true, {32, 48, 64}, 2},
                      OrderCase{CollocationFamily::kGaussLegendre, 2, true, {16, 24, 32}, 2}));

/// The standard method does not locate the switch: first order at best, whatever the scheme's
/// order (its errors scatter with where t_s = 1 falls in the grid, so a wide range is fitted).
TEST(SpiralStandardOrder, RadauIIAWithTwoStagesIsFirstOrder) {
  const double order =
      spiralOrder({CollocationFamily::kRadauIIA, 2, false, {16, 32, 64, 128, 256}, 2});
  EXPECT_GT(order, 0.5);
  EXPECT_LT(order, 1.5);
}

/// Nurkanovic et al. 2024 Sec. 4.6: from forward simulations of several initial values as guesses,
/// FESD (Gauss-Legendre, n_s = 2, 25 elements, homotopy) finds the analytic optimum of OCP (56).
TEST(SignOcp, FesdFindsTheAnalyticOptimumFromSeveralGuesses) {
  namespace example = fesd::sign_example;
  for (double guess : {-2.5, -1.5, -0.5}) {
    const example::Result result = example::solve(guess, true, fesd::HomotopyOptions{});
    EXPECT_EQ(result.guess_status, fesd::SolveStatus::kSuccess) << guess;
    EXPECT_EQ(result.status, fesd::SolveStatus::kSuccess) << guess;
    EXPECT_NEAR(result.initial_state, example::optimalInitialState(), 1e-4) << guess;
  }
}

/// With OcpSolver's two-stage homotopy (the standard method's grid until sigma = 1e-2, then
/// FESD) the optimum is found from constant guesses on either side of the switch too, where
/// the forward-simulation guesses of x0 >= 0 (no switch) leave pure FESD at another
/// stationary point.
TEST(SignOcp, OcpSolverFindsTheAnalyticOptimumFromGuessesOnEitherSide) {
  namespace example = fesd::sign_example;
  fesd::OcpOptions options;
  options.discretization = example::discretization(true);
  for (double guess : {-2.5, 0.5, 2.0}) {
    fesd::OcpSolver solver(example::ocp(guess), options);
    const fesd::OcpSolution solution = solver.solve();
    EXPECT_EQ(solution.status, fesd::SolveStatus::kSuccess) << guess;
    EXPECT_NEAR(solution.trajectory.states.front()(0), example::optimalInitialState(), 1e-6)
        << guess;
  }
}

/// Subsystems sliding in an element: both of their modes active (theta outweighs lambda).
std::set<int> slidingSubsystems(const fesd::ElementValues& element) {
  std::set<int> sliding;
  for (int k = 0; k < 2; ++k) {
    bool both = true;
    for (int mode = 2 * k; mode < 2 * k + 2; ++mode) {
      both &= element.stage_multipliers.row(mode).sum() > element.stage_constraints.row(mode).sum();
    }
    if (both) sliding.insert(k);
  }
  return sliding;
}

/// Nurkanovic et al. 2024 Sec. 5.3: OCP (61), Radau-IIA n_s = 2, 6 intervals of 6 elements.
TEST(SlidingOcp, SlidesOnASurfaceThenTheManifoldAndEqualisesSteps) {
  fesd::OcpOptions options;
  options.discretization.num_stages = 2;
  options.discretization.num_elements = 6;
  fesd::OcpSolver solver(fesd::sliding_ocp_example::ocp(), options);
  const fesd::OcpSolution solution = solver.solve();
  ASSERT_EQ(solution.status, fesd::SolveStatus::kSuccess) << solution.message;
  const fesd::Trajectory& trajectory = solution.trajectory;
  EXPECT_LT((trajectory.finalState().head(2) - fesd::sliding_ocp_example::targetPosition()).norm(),
            1e-8);
  // The controls reproduce the plan in a fine simulation.
  fesd::SimulationOptions fine;
  fine.discretization.num_stages = 4;
  fine.discretization.num_elements = 12;
  EXPECT_LT(fesd::resimulationError(fesd::sliding_ocp_example::ocp(), solution, fine), 1e-6);

  // Phases: free, sliding on one surface, on the manifold c(x) = 0, possibly on the other
  // surface, then free to the end.
  std::vector<std::set<int>> phases;
  for (const fesd::ElementValues& element : trajectory.elements) {
    const std::set<int> sliding = slidingSubsystems(element);
    if (phases.empty() || phases.back() != sliding) phases.push_back(sliding);
  }
  ASSERT_GE(phases.size(), 4u);
  ASSERT_LE(phases.size(), 5u);
  EXPECT_TRUE(phases.front().empty());
  EXPECT_EQ(phases[1].size(), 1u);
  EXPECT_EQ(phases[2], (std::set<int>{0, 1}));
  if (phases.size() == 5) {
    EXPECT_EQ(phases[3].size(), 1u);
    EXPECT_NE(phases[3], phases[1]);
  }
  EXPECT_TRUE(phases.back().empty());

  // Step equilibration: within a control interval the steps change only at a switch.
  std::set<int> switch_elements;
  for (const fesd::SwitchEvent& event : trajectory.switches) switch_elements.insert(event.element);
  int adapted_intervals = 0;
  for (int k = 0; k < 6; ++k) {
    bool adapted = false;
    for (int n = 1; n < 6; ++n) {
      const int element = 6 * k + n;
      const double change =
          std::fabs(trajectory.elements[element].step - trajectory.elements[element - 1].step);
      if (!switch_elements.count(element)) {
        EXPECT_LT(change, 1e-8) << "element " << element;
      }
      adapted |= change > 1e-3;
    }
    adapted_intervals += adapted;
  }
  EXPECT_GE(adapted_intervals, 1);  // the grid did move to the switches
  // eq. 31: where the steps change, the switch indicator vanishes.
  const auto& discretization =
      dynamic_cast<const fesd::StewartDiscretization&>(solver.discretization());
  const std::vector<double> indicators =
      discretization.switchIndicators(solution.report.solution.data());
  ASSERT_EQ(indicators.size(), 6u * 5u);
  for (int k = 0; k < 6; ++k) {
    for (int n = 1; n < 6; ++n) {
      const int element = 6 * k + n;
      if (std::fabs(trajectory.elements[element].step - trajectory.elements[element - 1].step) >
          1e-8) {
        EXPECT_LT(indicators[5 * k + n - 1], 1e-10) << "element " << element;
      }
    }
  }
}

}  // namespace
