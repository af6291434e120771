// The OCP layer: an LQ problem against its Riccati solution, and the collaborative manipulation
// showcase of Pozharskiy et al. 2024 Sec. IV-B with FESD and with the standard method.
#include <cmath>
#include <cstdlib>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/function/affine_function.h"
#include "fesd_trajopt/function/quadratic_function.h"
#include "fesd_trajopt/ocp/ocp_solver.h"

namespace {

/// xdot = u, no constraints; min int x^2 + u^2 dt from x(0) = 1 over [0, T]: the Riccati
/// solution has cost tanh(T) (free end state).
fesd::OcpDefinition linearQuadratic(double horizon, int intervals) {
  Eigen::SparseMatrix<double> velocity(1, 2), none(0, 1);
  velocity.insert(0, 1) = 1.0;
  fesd::OcpDefinition ocp;
  ocp.model = std::make_shared<fesd::DcsModel>(
      1, 1, 0, std::make_shared<fesd::AffineFunction>(velocity, Eigen::VectorXd::Zero(1)),
      std::make_shared<fesd::AffineFunction>(none, Eigen::VectorXd::Zero(0)), "integrator");
  ocp.initial_state = Eigen::VectorXd::Ones(1);
  ocp.horizon = horizon;
  ocp.num_intervals = intervals;
  ocp.lagrange_cost =
      fesd::QuadraticFunction::weightedDistance(Eigen::Vector2d::Ones(), Eigen::Vector2d::Zero());
  return ocp;
}

TEST(OptimalControl, LinearQuadraticMatchesTheRiccatiCost) {
  const double horizon = 2.0;
  fesd::OcpSolver solver(linearQuadratic(horizon, 50), fesd::OcpOptions{});
  const fesd::OcpSolution solution = solver.solve();
  ASSERT_EQ(solution.status, fesd::SolveStatus::kSuccess) << solution.message;
  EXPECT_EQ(solution.report.history.size(), 1u);  // smooth: no homotopy
  // Piecewise-constant controls on 50 intervals: O(h^2) above the continuous optimum.
  EXPECT_NEAR(solution.report.objective, std::tanh(horizon), 2e-3);
  EXPECT_GE(solution.report.objective, std::tanh(horizon) - 1e-6);
  // The optimal feedback is u = -tanh(T - t) x: u(0) = -tanh(T) to first order in h.
  EXPECT_NEAR(solution.trajectory.controls.front()(0), -std::tanh(horizon), 0.05);
}

TEST(OptimalControl, StateBoundsAndTerminalConstraintsHold) {
  fesd::OcpDefinition ocp = linearQuadratic(2.0, 20);
  ocp.state_lower = Eigen::VectorXd::Constant(1, 0.4);  // x >= 0.4 everywhere
  Eigen::SparseMatrix<double> minus_x(1, 1);
  minus_x.insert(0, 0) = -1.0;
  ocp.terminal_constraints =  // 0.6 - x(T) <= 0
      std::make_shared<fesd::AffineFunction>(minus_x, Eigen::VectorXd::Constant(1, 0.6));
  fesd::OcpSolver solver(ocp, fesd::OcpOptions{});
  const fesd::OcpSolution solution = solver.solve();
  ASSERT_EQ(solution.status, fesd::SolveStatus::kSuccess) << solution.message;
  for (const Eigen::VectorXd& x : solution.trajectory.states) EXPECT_GE(x(0), 0.4 - 1e-8);
  EXPECT_NEAR(solution.trajectory.finalState()(0), 0.6, 1e-7);  // the bound is active
}

struct ShowcaseRun {
  fesd::OcpSolution solution;
  double resimulation_error;
};

fesd::OcpOptions showcaseOptions(bool fesd_on) {
  fesd::OcpOptions options;
  options.discretization.num_stages = 2;
  options.discretization.num_elements = 3;
  options.discretization.switch_detection = fesd_on;
  return options;
}

/// The showcase (N = 40, N_FE = 3, n_s = 2) solved from its push plan, as the node solves it;
/// `perturbation` adds seeded relative noise of that size to the plan's states and controls.
ShowcaseRun solveShowcase(bool fesd_on, double perturbation = 0.0) {
  const fesd::OcpDefinition ocp = fesd::manipulation_example::ocp(40);
  fesd::TrajectoryGuess guess = fesd::manipulation_example::plan(40).guess;
  if (perturbation > 0.0) {
    std::srand(7);
    auto noisy = [perturbation](Eigen::VectorXd v) {
      for (int i = 0; i < v.size(); ++i) {
        v(i) *= 1.0 + perturbation * (2.0 * std::rand() / RAND_MAX - 1.0);
      }
      return v;
    };
    const auto state = guess.state;
    guess.state = [state, noisy](double t) { return noisy(state(t)); };
    for (Eigen::VectorXd& u : guess.controls) u = noisy(u);
  }
  fesd::OcpSolver solver(ocp, showcaseOptions(fesd_on));
  ShowcaseRun run{solver.solve(guess), 0.0};
  fesd::SimulationOptions fine;
  fine.discretization.num_stages = 3;
  fine.discretization.num_elements = 6;
  run.resimulation_error = fesd::resimulationError(ocp, run.solution, fine);
  ::testing::Test::RecordProperty(fesd_on ? "fesd_resim_error" : "standard_resim_error",
                                  std::to_string(run.resimulation_error));
  return run;
}

/// The objective of the showcase solved from its plan, as measured under reference BLAS and
/// OpenBLAS (Prescott, Haswell, SkylakeX kernels): the same to 12 digits under all four.
constexpr double kShowcaseObjective = 0.0552151506;

TEST(ManipulationShowcase, FesdSolvesItWithContactsReleasesAndThePlanHoldsUp) {
  const ShowcaseRun run = solveShowcase(true);
  const fesd::OcpSolution& solution = run.solution;
  ASSERT_EQ(solution.status, fesd::SolveStatus::kSuccess) << solution.message;
  EXPECT_EQ(solution.report.complementarity_residual, 0.0);
  EXPECT_TRUE(solution.report.b_stationary);
  EXPECT_TRUE(solution.trajectory.switchesResolved());
  EXPECT_NEAR(solution.report.objective / kShowcaseObjective, 1.0, 1e-4);
  EXPECT_LE(solution.report.iterations, 150);
  const Eigen::VectorXd& end = solution.trajectory.finalState();
  EXPECT_LT((end.tail<2>() - fesd::manipulation_example::objectGoal()).norm(), 1e-3);
  for (const Eigen::VectorXd& x : solution.trajectory.states) {  // every element boundary
    EXPECT_LE(x(0), -2.5 + 1e-6);
    EXPECT_GE(x(2), 2.5 - 1e-6);
  }
  // Both actuators touch the object once and let go once.
  ASSERT_EQ(solution.trajectory.switches.size(), 4u);
  int contacts = 0;
  for (const fesd::SwitchEvent& event : solution.trajectory.switches) {
    contacts += event.kind == fesd::SwitchEvent::Kind::kContact;
  }
  EXPECT_EQ(contacts, 2);
  // Re-simulated on a finer grid (3 stages, 6 elements per interval). This plan amplifies state
  // errors made in the contact interval about 250-fold (README); measured 1.9e-3.
  EXPECT_LT(run.resimulation_error, 1e-2);
  std::printf(
      "FESD showcase: objective %.10g, resimulation error %.3g, %d Ipopt iterations, "
      "%.2f s\n",
      solution.report.objective, run.resimulation_error, solution.report.iterations,
      solution.report.wall_seconds);
}

TEST(ManipulationShowcase, TheSolutionDoesNotHingeOnRounding) {
  // Relative noise of 1e-9 on the plan stands for rounding far larger than any BLAS kernel's:
  // the solve must end at the same point, not in a neighbouring local optimum.
  const ShowcaseRun exact = solveShowcase(true), perturbed = solveShowcase(true, 1e-9);
  ASSERT_EQ(perturbed.solution.status, fesd::SolveStatus::kSuccess) << perturbed.solution.message;
  EXPECT_NEAR(perturbed.solution.report.objective / exact.solution.report.objective, 1.0, 1e-8);
  const auto& switches = exact.solution.trajectory.switches;
  const auto& perturbed_switches = perturbed.solution.trajectory.switches;
  ASSERT_EQ(perturbed_switches.size(), switches.size());
  for (size_t k = 0; k < switches.size(); ++k) {
    EXPECT_EQ(perturbed_switches[k].constraint, switches[k].constraint);
    EXPECT_EQ(perturbed_switches[k].kind, switches[k].kind);
    EXPECT_NEAR(perturbed_switches[k].time, switches[k].time, 1e-6);
  }
  EXPECT_LT(
      (perturbed.solution.trajectory.finalState() - exact.solution.trajectory.finalState()).norm(),
      1e-6);
}

TEST(ManipulationShowcase, WarmStartFromAPreviousSolutionConvergesAtOnce) {
  const fesd::OcpDefinition ocp = fesd::manipulation_example::ocp(30);
  fesd::OcpOptions options;
  options.discretization.num_elements = 2;
  fesd::OcpSolver solver(ocp, options);
  const fesd::OcpSolution first = solver.solve(fesd::manipulation_example::plan(30).guess);
  ASSERT_EQ(first.status, fesd::SolveStatus::kSuccess) << first.message;
  const fesd::OcpSolution again = solver.solve(first);
  ASSERT_EQ(again.status, fesd::SolveStatus::kSuccess) << again.message;
  // The same task again: polishing from the previous active set may still improve the point
  // (its Ipopt start is tuned for changed tasks, OcpOptions::warm_start_mu): 0 iterations here
  // against 28 (13 against 33 when warm starts kept a monotone barrier).
  EXPECT_LE(again.report.objective, first.report.objective + 1e-6);
  EXPECT_GT(again.report.objective, first.report.objective - 1e-3);
  EXPECT_LT(again.report.iterations, first.report.iterations / 2);
}

// Optimal control frees Ipopt's barrier in warm starts (optimalControlHomotopy): a tighter
// relaxation moves the contacts, which a barrier fixed at 1e-6 sigma reached in small steps. The
// same optimum in fewer iterations than with the monotone barrier.
TEST(ManipulationShowcase, AFreeBarrierInWarmStartsReachesTheSameOptimumInFewerIterations) {
  const fesd::OcpDefinition ocp = fesd::manipulation_example::ocp(30);
  const fesd::TrajectoryGuess guess = fesd::manipulation_example::plan(30).guess;
  fesd::OcpOptions options;
  options.discretization.num_elements = 2;
  const fesd::OcpSolution free_barrier = fesd::OcpSolver(ocp, options).solve(guess);
  options.homotopy.ipopt.warm_start_barrier = fesd::BarrierStrategy{};  // monotone
  options.homotopy.ipopt.near_solution_barrier = fesd::BarrierStrategy{};
  const fesd::OcpSolution monotone = fesd::OcpSolver(ocp, options).solve(guess);
  ASSERT_EQ(free_barrier.status, fesd::SolveStatus::kSuccess) << free_barrier.message;
  ASSERT_EQ(monotone.status, fesd::SolveStatus::kSuccess) << monotone.message;
  std::printf("showcase from its plan: %d Ipopt iterations, monotone warm starts %d\n",
              free_barrier.report.iterations, monotone.report.iterations);
  EXPECT_NEAR(free_barrier.report.objective, monotone.report.objective,
              1e-8 * monotone.report.objective);
  EXPECT_LT(free_barrier.report.iterations, monotone.report.iterations);
}

TEST(ManipulationShowcase, StandardMethodOnTheSameGridForComparison) {
  const ShowcaseRun run = solveShowcase(false);
  ASSERT_EQ(run.solution.status, fesd::SolveStatus::kSuccess) << run.solution.message;
  EXPECT_LT(
      (run.solution.trajectory.finalState().tail<2>() - fesd::manipulation_example::objectGoal())
          .norm(),
      0.1);
  std::printf("standard showcase: resimulation error %.3g, %d Ipopt iterations, %.2f s\n",
              run.resimulation_error, run.solution.report.iterations,
              run.solution.report.wall_seconds);
}

}  // namespace
