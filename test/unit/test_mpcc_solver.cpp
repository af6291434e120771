// The homotopy solver on tiny problems with known answers, and its status reporting.
#include <gtest/gtest.h>

#include "fesd_trajopt/function/affine_function.h"
#include "support/corner_mpcc.h"

namespace {

using CornerMpcc = fesd_test::CornerMpcc<>;

TEST(MpccSolver, ScholtesHomotopyReachesAStronglyStationaryPoint) {
  CornerMpcc problem;
  const fesd::MpccReport report = problem.solve();
  ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess) << report.message;
  EXPECT_NEAR(report.solution[problem.x], 1.0, 1e-6);
  EXPECT_NEAR(report.solution[problem.y], 0.0, 1e-6);
  EXPECT_NEAR(report.objective, 1.0, 1e-6);
  EXPECT_LE(report.complementarity_residual, 1e-9);
  // sigma0 = 1, kappa = 0.1 (the notes' defaults): residual ~ sigma, so about ten steps.
  ASSERT_GE(report.history.size(), 2u);
  EXPECT_DOUBLE_EQ(report.history[0].sigma, 1.0);
  EXPECT_DOUBLE_EQ(report.history[1].sigma, 0.1);
  EXPECT_GT(report.iterations, 0);
  EXPECT_GE(report.wall_seconds, report.ipopt_seconds);
}

TEST(MpccSolver, EarlyPolishingEndsTheHomotopyAtABStationaryPoint) {
  CornerMpcc problem;
  fesd::HomotopyOptions options;
  options.early_polish_sigma = 1e-2;
  const fesd::MpccReport report = problem.solve(options);
  ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess) << report.message;
  // sigma = 1, 0.1, 0.01 and 0.001 (the same active set twice), then the polished NLP
  // (sigma 0) that is accepted at once.
  ASSERT_EQ(report.history.size(), 5u);
  EXPECT_DOUBLE_EQ(report.history[3].sigma, 1e-3);
  EXPECT_DOUBLE_EQ(report.history[4].sigma, 0.0);
  EXPECT_TRUE(report.polished);
  EXPECT_TRUE(report.b_stationary);
  EXPECT_EQ(report.complementarity_residual, 0.0);
  EXPECT_NEAR(report.solution[problem.x], 1.0, 1e-8);
  EXPECT_NEAR(report.solution[problem.y], 0.0, 1e-8);
}

TEST(MpccSolver, AnEarlyPolishThatSucceedsIsNotPolishedAgain) {
  CornerMpcc problem;
  fesd::HomotopyOptions options;
  // Early polishing at a relaxation whose residual is below polish_rescue_residual (1e-4): the
  // rescue polish of a homotopy that did not converge must not run after it succeeded.
  options.early_polish_sigma = 1e-4;
  const fesd::MpccReport report = problem.solve(options);
  ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess) << report.message;
  int polishes = 0;
  for (const fesd::HomotopyStep& step : report.history) polishes += step.sigma == 0.0;
  EXPECT_EQ(polishes, 1);
  EXPECT_DOUBLE_EQ(report.history.back().sigma, 0.0);
  EXPECT_DOUBLE_EQ(report.history[report.history.size() - 2].sigma, 1e-5);
  EXPECT_TRUE(report.b_stationary);
}

/// min -x  s.t.  y = x,  0 <= x _|_ y >= 0 (and an unrelated pair): the origin is the only feasible
/// point, so it is B-stationary, but with x fixed to 0 the row y = x pins the free side y to 0 as
/// well and every multiplier gives d Lagrangian / dx = -1 - z_y < 0: the multiplier test says
/// "descent". The other branch (y fixed, x free) keeps the point, which confirms it.
TEST(MpccSolver, TheOtherBranchConfirmsAPointTheMultipliersCannot) {
  for (const int check : {30, 0}) {
    fesd::NlpAssembly nlp;
    const int x = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    const int y = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    const int row = nlp.addRows(1, 0.0, 0.0);
    nlp.addLinear(row, {{y, 1.0}, {x, -1.0}});
    Eigen::SparseMatrix<double> minus_x(1, 1);
    minus_x.insert(0, 0) = -1.0;
    nlp.addFunctionTerm(std::make_shared<fesd::AffineFunction>(minus_x, Eigen::VectorXd::Zero(1)),
                        {x}, -1, {{fesd::NlpAssembly::kObjective, 1.0}});
    nlp.addComplementarity({{x, 1.0}}, {{y, 1.0}});
    // A second pair, u = 1 _|_ v = 0, gives the scale on which y counts as zero.
    const int u = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    const int v = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    nlp.addFunctionTerm(fesd::QuadraticFunction::weightedDistance(Eigen::Vector2d::Ones(),
                                                                  Eigen::Vector2d(1.0, 0.0)),
                        {u, v}, -1, {{fesd::NlpAssembly::kObjective, 1.0}});
    nlp.addComplementarity({{u, 1.0}}, {{v, 1.0}});
    nlp.finalize();
    fesd::HomotopyOptions options;
    options.early_polish_sigma = 1e-2;
    options.branch_check_iterations = check;
    const fesd::MpccReport report = fesd::MpccSolver(options).solve(nlp, {0.5, 0.5, 1.0, 0.1});
    ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess) << report.message;
    EXPECT_NEAR(report.solution[x], 0.0, 1e-8);
    EXPECT_NEAR(report.solution[y], 0.0, 1e-8);
    if (check > 0) {
      // sigma = 1, 0.1, 0.01, 0.001, the polished NLP and the other branch: accepted there.
      EXPECT_TRUE(report.b_stationary) << report.message;
      EXPECT_EQ(report.history.size(), 6u);
    } else {
      EXPECT_GT(report.history.size(), 6u);  // the homotopy goes on
    }
  }
}

TEST(MpccSolver, SmoothProblemIsSolvedOnceWithoutHomotopy) {
  fesd::NlpAssembly nlp;
  const int x = nlp.addVariables(2, -10.0, 10.0);
  nlp.addFunctionTerm(fesd::QuadraticFunction::weightedDistance(Eigen::Vector2d(1.0, 2.0),
                                                                Eigen::Vector2d(3.0, -4.0)),
                      {x, x + 1}, -1, {{fesd::NlpAssembly::kObjective, 1.0}});
  nlp.finalize();
  fesd::MpccSolver solver;
  const fesd::MpccReport report = solver.solve(nlp, {0.0, 0.0});
  ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess);
  EXPECT_EQ(report.history.size(), 1u);
  EXPECT_NEAR(report.solution[0], 3.0, 1e-8);
  EXPECT_NEAR(report.solution[1], -4.0, 1e-8);
}

/// min (x-1)^2 + (y-1)^2 + sigma (x-2)^2  s.t.  0 <= x _|_ y >= 0, the last term vanishing with
/// the relaxation (as FESD's step regulariser): the polished solution keeps it at the relaxation
/// it was polished at, x = (1 + 2 s) / (1 + s), and a warm start from it must solve that same
/// objective, not the one at sigma = 0 (x = 1).
TEST(MpccSolver, AWarmStartPolishesWithTheObjectiveOfThePointItStartsFrom) {
  fesd_test::CornerMpcc<> problem;
  problem.nlp.addFunctionTerm(fesd::QuadraticFunction::weightedDistance(
                                  Eigen::VectorXd::Ones(1), Eigen::VectorXd::Constant(1, 2.0)),
                              {problem.x}, -1, {{fesd::NlpAssembly::kObjective, 1.0, true}});
  const fesd::MpccReport cold = problem.solve();
  ASSERT_EQ(cold.status, fesd::SolveStatus::kSuccess) << cold.message;
  ASSERT_TRUE(cold.polished);
  const double s = cold.polish_sigma;
  ASSERT_GT(s, 0.0);
  EXPECT_NEAR(cold.solution[problem.x], (1.0 + 2.0 * s) / (1.0 + s), 1e-8);
  problem.nlp.setRelaxation(0.0);  // as a new NLP of the same task starts
  fesd::MpccSolver solver;
  const fesd::MpccReport warm = solver.solve(problem.nlp, cold, 1e-2);
  ASSERT_EQ(warm.status, fesd::SolveStatus::kSuccess) << warm.message;
  EXPECT_EQ(warm.history.size(), 1u);  // polished at once
  EXPECT_NEAR(warm.solution[problem.x], cold.solution[problem.x], 1e-8);
  EXPECT_NEAR(warm.objective, cold.objective, 1e-10);
  EXPECT_EQ(warm.polish_sigma, s);
}

TEST(MpccSolver, WarmStartFromAProblemWithOtherRowsDropsItsMultipliers) {
  CornerMpcc previous;
  const fesd::MpccReport solved = previous.solve();
  ASSERT_EQ(solved.status, fesd::SolveStatus::kSuccess) << solved.message;
  // The same variables and one more row (x + y <= 3, inactive): the old constraint
  // multipliers do not fit, so the warm start (and its polishing) goes without them.
  CornerMpcc extended;
  const int row = extended.nlp.addRows(1, -fesd::NlpAssembly::kInfinity, 3.0);
  extended.nlp.addLinear(row, {{extended.x, 1.0}, {extended.y, 1.0}});
  extended.nlp.finalize();
  fesd::MpccSolver solver;
  const fesd::MpccReport report = solver.solve(extended.nlp, solved, 1e-4);
  ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess) << report.message;
  EXPECT_NEAR(report.solution[extended.x], 1.0, 1e-8);
  EXPECT_NEAR(report.solution[extended.y], 0.0, 1e-8);
  EXPECT_LE(report.complementarity_residual, 1e-9);
}

TEST(MpccSolver, ReportsInfeasibility) {
  CornerMpcc problem;
  const int row = problem.nlp.addRows(1, -fesd::NlpAssembly::kInfinity, -1.0);  // x + y <= -1
  problem.nlp.addLinear(row, {{problem.x, 1.0}, {problem.y, 1.0}});
  fesd::HomotopyOptions options;
  options.max_steps = 3;
  const fesd::MpccReport report = problem.solve(options);
  EXPECT_EQ(report.status, fesd::SolveStatus::kInfeasible) << report.message;
  EXPECT_NE(report.message.find("infeasible"), std::string::npos);
}

TEST(MpccSolver, ReportsTheIterationLimit) {
  fesd::HomotopyOptions options;
  options.ipopt.max_iterations = 1;
  options.continue_after_failure = false;
  const fesd::MpccReport report = CornerMpcc().solve(options);
  EXPECT_EQ(report.status, fesd::SolveStatus::kMaxIterations) << report.message;
}

TEST(MpccSolver, HonoursTheWallTimeBudgetAndKeepsTheIterate) {
  fesd::HomotopyOptions options;
  options.wall_time_budget = 0.0;
  const fesd::MpccReport report = CornerMpcc().solve(options);
  EXPECT_EQ(report.status, fesd::SolveStatus::kTimeout) << report.message;
  EXPECT_EQ(report.history.size(), 1u);
  EXPECT_EQ(report.solution.size(), 2u);
}

TEST(MpccSolver, RejectsUnknownIpoptOptions) {
  fesd::HomotopyOptions options;
  options.ipopt.extra_options["no_such_option"] = "1";
  EXPECT_THROW(fesd::MpccSolver solver(options), std::invalid_argument);
}

}  // namespace
