// Robustness of the homotopy loop: a relaxed NLP that fails (once, or in a row up to a limit),
// exceptions from the problem, the wall-time budget, and repeatability (same input, bitwise the
// same output).
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <thread>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/circle_example.h"
#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "support/corner_mpcc.h"
#include "support/scene_tasks.h"

namespace {

/// The corner MPCC's assembly with a fault while sigma is in [fault_from, fault_to]: the
/// objective is NaN there, or its evaluation throws, or (a setup fault) the bounds throw.
class FaultyAssembly : public fesd::NlpAssembly {
 public:
  enum class Fault { kNaN, kThrow, kThrowInSetup };
  Fault fault = Fault::kNaN;
  double fault_from = 0.0, fault_to = -1.0;
  /// A slow problem: objective evaluations at sigma < slow_below, after the first
  /// fast_evaluations, sleep this long.
  double evaluation_delay = 0.0, slow_below = 1.0;
  int fast_evaluations = 0;

  void setRelaxation(double sigma) override {
    sigma_ = sigma;
    NlpAssembly::setRelaxation(sigma);
  }
  double objective(const double* x) const override {
    if (evaluation_delay > 0.0 && sigma_ < slow_below && ++evaluations_ > fast_evaluations) {
      std::this_thread::sleep_for(std::chrono::duration<double>(evaluation_delay));
    }
    if (faulty() && fault == Fault::kNaN) return std::nan("");
    if (faulty() && fault == Fault::kThrow) throw std::runtime_error("injected evaluation fault");
    return NlpAssembly::objective(x);
  }
  void getBounds(double* x_lower, double* x_upper, double* g_lower,
                 double* g_upper) const override {
    if (faulty() && fault == Fault::kThrowInSetup) throw std::runtime_error("injected setup fault");
    NlpAssembly::getBounds(x_lower, x_upper, g_lower, g_upper);
  }

 private:
  bool faulty() const { return fault_from <= sigma_ && sigma_ <= fault_to; }
  double sigma_ = 1.0;
  mutable int evaluations_ = 0;
};

using FaultyCorner = fesd_test::CornerMpcc<FaultyAssembly>;

TEST(SolverRobustness, AFailedRelaxedNlpIsSkippedOrStopsTheHomotopyWithAClearStatus) {
  for (const FaultyAssembly::Fault fault :
       {FaultyAssembly::Fault::kNaN, FaultyAssembly::Fault::kThrow}) {
    // The relaxed NLP at sigma = 1e-2 fails at its first evaluation.
    FaultyCorner continuing;
    continuing.nlp.fault = fault;
    continuing.nlp.fault_from = 5e-3;
    continuing.nlp.fault_to = 2e-2;
    const fesd::MpccReport after_failure = continuing.solve();
    // The next, tighter NLP starts from the failed one's point and the homotopy recovers.
    ASSERT_EQ(after_failure.status, fesd::SolveStatus::kSuccess) << after_failure.message;
    EXPECT_EQ(after_failure.failedSteps(), 1);
    EXPECT_EQ(after_failure.history[2].ipopt_status, "invalid_number_detected");
    EXPECT_NEAR(after_failure.solution[continuing.x], 1.0, 1e-6);
    EXPECT_LE(after_failure.complementarity_residual, 1e-9);

    FaultyCorner stopping;
    stopping.nlp.fault = fault;
    stopping.nlp.fault_from = 5e-3;
    stopping.nlp.fault_to = 2e-2;
    fesd::HomotopyOptions options;
    options.max_consecutive_failures = 1;
    const fesd::MpccReport stopped = stopping.solve(options);
    EXPECT_EQ(stopped.status, fesd::SolveStatus::kSolverError) << stopped.message;
    EXPECT_EQ(stopped.history.size(), 3u);  // sigma = 1, 0.1, 0.01
    EXPECT_NE(stopped.message.find("invalid_number_detected"), std::string::npos)
        << stopped.message;
    for (double v : stopped.solution) EXPECT_TRUE(std::isfinite(v));
  }
}

TEST(SolverRobustness, FailedRelaxedNlpsInARowStopTheHomotopyAtTheirLimit) {
  // Faults at sigma = 1e-2 alone, or at 1e-2 and 1e-3: two failures in a row only in the second.
  const auto solveWithFaults = [](double fault_from, int limit) {
    FaultyCorner problem;
    problem.nlp.fault_from = fault_from;
    problem.nlp.fault_to = 2e-2;
    fesd::HomotopyOptions options;
    options.max_consecutive_failures = limit;
    return problem.solve(options);
  };
  const fesd::MpccReport one_failure = solveWithFaults(5e-3, 2);
  EXPECT_EQ(one_failure.status, fesd::SolveStatus::kSuccess) << one_failure.message;
  EXPECT_EQ(one_failure.failedSteps(), 1);

  const fesd::MpccReport two_failures = solveWithFaults(5e-4, 2);
  EXPECT_EQ(two_failures.status, fesd::SolveStatus::kSolverError) << two_failures.message;
  EXPECT_EQ(two_failures.history.size(), 4u);  // sigma = 1, 0.1, 0.01, 0.001
  EXPECT_EQ(two_failures.failedSteps(), 2);

  const fesd::MpccReport without_limit = solveWithFaults(5e-4, 0);
  EXPECT_EQ(without_limit.status, fesd::SolveStatus::kSuccess) << without_limit.message;
  EXPECT_EQ(without_limit.failedSteps(), 2);
  EXPECT_LE(without_limit.complementarity_residual, 1e-9);
}

TEST(SolverRobustness, ProblemsThatFailEverywhereEndWithSolverErrorNotACrash) {
  for (const FaultyAssembly::Fault fault :
       {FaultyAssembly::Fault::kNaN, FaultyAssembly::Fault::kThrow,
        FaultyAssembly::Fault::kThrowInSetup}) {
    FaultyCorner problem;
    problem.nlp.fault = fault;
    problem.nlp.fault_to = 1e9;
    fesd::HomotopyOptions options;
    options.max_steps = 5;
    const fesd::MpccReport report = problem.solve(options);
    EXPECT_EQ(report.status, fesd::SolveStatus::kSolverError) << report.message;
    EXPECT_EQ(report.failedSteps(), 5);
    EXPECT_NE(report.message.find(fault == FaultyAssembly::Fault::kThrowInSetup
                                      ? "non_ipopt_exception"
                                      : "invalid_number_detected"),
              std::string::npos)
        << report.message;
    EXPECT_EQ(report.solution, (std::vector<double>{1.0, 0.5}));  // the guess, untouched
  }
}

TEST(SolverRobustness, InfeasibleRelaxationsInARowEndTheHomotopy) {
  fesd_test::CornerMpcc<> problem;
  const int row = problem.nlp.addRows(1, -fesd::NlpAssembly::kInfinity, -1.0);  // x + y <= -1
  problem.nlp.addLinear(row, {{problem.x, 1.0}, {problem.y, 1.0}});
  const fesd::MpccReport report = problem.solve();
  EXPECT_EQ(report.status, fesd::SolveStatus::kInfeasible) << report.message;
  EXPECT_EQ(report.history.size(), 3u);  // HomotopyOptions::max_consecutive_infeasible
  for (const fesd::HomotopyStep& step : report.history) {
    EXPECT_EQ(step.ipopt_status, "infeasible_problem_detected");
  }
}

TEST(SolverRobustness, ATimeoutReturnsTheBestConvergedRelaxedSolution) {
  // sigma = 1 solves at once; from sigma = 0.1 on every evaluation takes 0.2 s, so a 1 s budget
  // ends inside a later relaxed NLP.
  FaultyCorner problem;
  problem.nlp.evaluation_delay = 0.2;
  fesd::HomotopyOptions options;
  options.wall_time_budget = 1.0;
  const fesd::MpccReport report = problem.solve(options);
  ASSERT_EQ(report.status, fesd::SolveStatus::kTimeout) << report.message;
  ASSERT_GE(report.history.size(), 2u);
  EXPECT_EQ(report.history.back().ipopt_status, "stopped_at_deadline");
  double best = INFINITY, best_sigma = 0.0;
  for (const fesd::HomotopyStep& step : report.history) {
    if (step.converged && step.complementarity_residual < best) {
      best = step.complementarity_residual;
      best_sigma = step.sigma;
    }
  }
  ASSERT_TRUE(std::isfinite(best)) << report.message;
  EXPECT_EQ(report.complementarity_residual, best);
  // A solution of that relaxed NLP: feasible for 0 <= x, y and x y <= sigma.
  const double x = report.solution[problem.x], y = report.solution[problem.y];
  EXPECT_GE(x, 0.0);
  EXPECT_GE(y, 0.0);
  EXPECT_LE(x * y, best_sigma * (1.0 + 1e-6));
  EXPECT_NEAR(report.objective, (x - 1.0) * (x - 1.0) + (y - 1.0) * (y - 1.0), 1e-9);
  ::testing::Test::RecordProperty("timeout_wall_seconds", std::to_string(report.wall_seconds));
}

TEST(SolverRobustness, ATimeoutBeforeAnyConvergenceKeepsTheMoreFeasibleOfStartAndIterate) {
  // On the circle x^2 + y^2 = 1 from the feasible start (0.6, 0.8); after three quick objective
  // evaluations each takes 0.3 s, so a 0.2 s budget stops the first NLP after an iteration or
  // two. Ipopt's iterate then lies off the circle (its steps follow the tangent): the start is
  // the better point to return.
  FaultyCorner problem;
  const int row = problem.nlp.addRows(1, 1.0, 1.0);
  problem.nlp.addFunctionTerm(
      fesd::QuadraticFunction::weightedDistance(Eigen::Vector2d::Ones(), Eigen::Vector2d::Zero()),
      {problem.x, problem.y}, -1, {{row, 1.0}});
  problem.nlp.evaluation_delay = 0.3;
  problem.nlp.slow_below = 2.0;
  problem.nlp.fast_evaluations = 3;
  problem.nlp.finalize();
  fesd::HomotopyOptions options;
  options.wall_time_budget = 0.2;
  const fesd::MpccReport report = fesd::MpccSolver(options).solve(problem.nlp, {0.6, 0.8});
  ASSERT_EQ(report.status, fesd::SolveStatus::kTimeout) << report.message;
  ASSERT_EQ(report.history.size(), 1u);
  EXPECT_EQ(report.solution, (std::vector<double>{0.6, 0.8}));
  EXPECT_NEAR(report.objective, 0.4 * 0.4 + 0.2 * 0.2, 1e-15);
  EXPECT_NEAR(report.complementarity_residual, 0.48, 1e-15);
}

TEST(SolverRobustness, ATinyBudgetStopsTheShowcaseOcpAtOnceWithAFiniteIterate) {
  fesd::OcpOptions options;
  options.homotopy.wall_time_budget = 1e-9;  // spent before the first check on any machine
  fesd::OcpSolver solver(fesd::manipulation_example::ocp(40), options);
  const fesd::OcpSolution solution = solver.solve();
  ASSERT_EQ(solution.status, fesd::SolveStatus::kTimeout) << solution.message;
  // Stopped in the first relaxed NLP after at most a couple of iterations (the full solve
  // takes 11 homotopy steps and about 400 iterations).
  EXPECT_EQ(solution.report.history.size(), 1u);
  EXPECT_LE(solution.report.iterations, 3);
  EXPECT_NE(solution.message.find("timeout"), std::string::npos);
  ASSERT_EQ(solution.trajectory.states.size(), solution.trajectory.times.size());
  for (const Eigen::VectorXd& x : solution.trajectory.states) EXPECT_TRUE(x.allFinite());
  for (const Eigen::VectorXd& u : solution.trajectory.controls) EXPECT_TRUE(u.allFinite());
  std::printf("tiny budget: %s after %.3f s\n", solution.message.c_str(),
              solution.report.wall_seconds);
}

TEST(SolverRobustness, ASimulationBudgetEndsTheSimulationWithTimeoutAndKeepsTheStepsDone) {
  namespace example = fesd::circle_example;
  fesd::SimulationOptions options;
  // Active-set steps take well under 0.1 ms each: 40 steps all finished within the 1 ms budget,
  // so the simulation asks for thousands. Without refinement every step has 2 elements, however
  // far it gets.
  constexpr int kSteps = 4000;
  options.wall_time_budget = 1e-3;
  options.refine_elements = false;
  fesd::FesdIntegrator integrator(example::model(), options);
  const fesd::SimulationResult result =
      integrator.simulate(example::initialState(), example::horizon(), kSteps);
  ASSERT_EQ(result.status, fesd::SolveStatus::kTimeout) << result.message;
  EXPECT_LT(result.completed_steps, kSteps);
  EXPECT_NE(result.message.find("timeout"), std::string::npos) << result.message;
  // The steps done and the interrupted one, each of 2 elements.
  EXPECT_EQ(result.trajectory.elements.size(), 2u * (result.completed_steps + 1));
  for (const Eigen::VectorXd& x : result.trajectory.states) EXPECT_TRUE(x.allFinite());
  std::printf("simulation budget 1 ms: %d of %d steps, %.3f s\n", result.completed_steps, kSteps,
              result.totals.wall_seconds);
}

TEST(SolverRobustness, TwentyRepeatsOfOneOcpAreBitwiseIdentical) {
  // A pusher drives a puck to a target 2 m on: contact, pushing, 6 intervals of 2 elements.
  fesd::SceneTask task = fesd_test::pushAlongX();
  task.bodies[0].max_speed = 3.0;
  task.bodies[1].target = Eigen::Vector2d(2.0, 0.0);
  task.bodies[1].target_weight = 10.0;
  task.num_intervals = 6;
  std::vector<fesd::ContactPair> pairs;
  for (const fesd::PairDecision& decision : fesd::decidePairs(task)) pairs.push_back(decision.pair);
  const fesd::OcpDefinition ocp = fesd::buildOcp(task, pairs);
  fesd::OcpOptions options;
  options.discretization.num_elements = 2;
  fesd::OcpSolver reused(ocp, options);
  const fesd::OcpSolution first = reused.solve();
  ASSERT_EQ(first.status, fesd::SolveStatus::kSuccess) << first.message;
  ASSERT_FALSE(first.trajectory.switches.empty());
  EXPECT_NEAR(first.trajectory.finalState()(2), 2.0, 0.01);
  for (int repeat = 1; repeat < 20; ++repeat) {
    // Every other repeat on a fresh solver, the rest on the same Ipopt application.
    fesd::OcpSolver fresh(ocp, options);
    const fesd::OcpSolution again = repeat % 2 ? fresh.solve() : reused.solve();
    EXPECT_EQ(again.status, first.status);
    EXPECT_EQ(again.report.solution, first.report.solution) << "repeat " << repeat;
    EXPECT_EQ(again.report.iterations, first.report.iterations);
    EXPECT_EQ(again.report.objective, first.report.objective);
  }
}

}  // namespace
