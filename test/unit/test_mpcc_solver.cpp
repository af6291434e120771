// The homotopy solver on tiny problems with known answers, and its status reporting.
#include <gtest/gtest.h>

#include <limits>
#include <utility>
#include <vector>

#include "fesd_trajopt/function/affine_function.h"
#include "support/corner_mpcc.h"

namespace {

using CornerMpcc = fesd_test::CornerMpcc<>;

/// The corner problem's strongly stationary point (x, y) = (1, 0), objective 1, to the tolerance.
void expectTheCorner(const CornerMpcc& problem, const fesd::MpccReport& report) {
  ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess) << report.message;
  EXPECT_NEAR(report.solution[problem.x], 1.0, 1e-6);
  EXPECT_NEAR(report.solution[problem.y], 0.0, 1e-6);
  EXPECT_NEAR(report.objective, 1.0, 1e-6);
  EXPECT_LE(report.complementarity_residual, 1e-9);
}

TEST(MpccSolver, ScholtesHomotopyReachesAStronglyStationaryPoint) {
  CornerMpcc problem;
  const fesd::MpccReport report = problem.solve();
  expectTheCorner(problem, report);
  // sigma0 = 1, kappa = 0.1 (the notes' defaults): residual ~ sigma, so about ten steps.
  ASSERT_GE(report.history.size(), 2u);
  EXPECT_DOUBLE_EQ(report.history[0].sigma, 1.0);
  EXPECT_DOUBLE_EQ(report.history[1].sigma, 0.1);
  EXPECT_GT(report.iterations, 0);
  EXPECT_GE(report.wall_seconds, report.ipopt_seconds);
}

TEST(MpccSolver, AHomotopyFollowingTheBarrierReachesTheSameStronglyStationaryPoint) {
  CornerMpcc problem;
  fesd::HomotopyOptions options;
  options.barrier_factor = 1e-2;
  const fesd::MpccReport report = problem.solve(options);
  expectTheCorner(problem, report);
  // Each relaxed NLP ends centred at mu = 1e-2 sigma and the next starts there: once the
  // corner is decided (sigma 1e-2) a step of the homotopy is a Newton step or two (solved to
  // convergence each takes 28 iterations at sigma 1e-3, then 1).
  ASSERT_EQ(report.history.size(), 11u);
  for (std::size_t step = 3; step < report.history.size(); ++step) {
    EXPECT_LE(report.history[step].iterations, 2) << "sigma " << report.history[step].sigma;
  }
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
    fesd_test::OnlyTheOrigin problem;
    const int x = problem.x, y = problem.y;
    problem.addScalePairAndFinalize();
    fesd::HomotopyOptions options;
    options.early_polish_sigma = 1e-2;
    options.branch_check_iterations = check;
    const fesd::MpccReport report =
        fesd::MpccSolver(options).solve(problem.nlp, {0.5, 0.5, 1.0, 0.1});
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

/// The same point with a branch check of one iteration, which cannot solve the other branch:
/// nothing is shown either way. By default the homotopy goes on; accepting an unsolved check
/// keeps the polished point, not claimed B-stationary.
TEST(MpccSolver, AnUnsolvedBranchCheckKeepsThePointOnlyWhereAccepted) {
  for (const bool accept : {false, true}) {
    fesd_test::OnlyTheOrigin problem;
    const fesd::MpccReport report = problem.solveWithAnUnsolvedBranchCheck(accept);
    ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess) << report.message;
    EXPECT_NEAR(report.solution[problem.x], 0.0, 1e-8);
    ASSERT_GE(report.history.size(), 6u);
    EXPECT_FALSE(report.history[5].converged);  // the one-iteration check
    if (accept) {
      EXPECT_EQ(report.history.size(), 6u) << report.message;
      EXPECT_FALSE(report.b_stationary);
    } else {
      EXPECT_GT(report.history.size(), 6u);
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

/// The solution (1, 0) of the corner and a row x <= 1 - depth it violates by `depth`, as a graze
/// round adds a guard the plan cuts into.
struct CutCorner {
  CornerMpcc solved, cut;
  fesd::MpccReport solution;
  explicit CutCorner(double depth) {
    solution = solved.solve();
    const int row = cut.nlp.addRows(1, -fesd::NlpAssembly::kInfinity, 1.0 - depth);
    cut.nlp.addLinear(row, {{cut.x, 1.0}});
    cut.nlp.finalize();
  }
};

TEST(MpccSolver, AStartNextToASolutionWithoutMultipliersStaysNextToIt) {
  CutCorner corner(1e-4);
  ASSERT_EQ(corner.solution.status, fesd::SolveStatus::kSuccess) << corner.solution.message;
  fesd::MpccSolver solver;
  const fesd::MpccReport near =
      solver.solveNearSolution(corner.cut.nlp, corner.solution.solution, 1e-4, -1.0);
  const fesd::MpccReport cold = solver.solve(corner.cut.nlp, corner.solution.solution, 1e-4);
  for (const fesd::MpccReport* report : {&near, &cold}) {
    ASSERT_EQ(report->status, fesd::SolveStatus::kSuccess) << report->message;
    EXPECT_NEAR(report->solution[corner.cut.x], 1.0 - 1e-4, 1e-8);
    EXPECT_NEAR(report->solution[corner.cut.y], 0.0, 1e-8);
  }
  // Ipopt's cold start re-centres the point (mu = 0.1, pushed 1e-2 off its bounds).
  EXPECT_LT(near.iterations, cold.iterations) << near.iterations << " against " << cold.iterations;
  // The near start changed Ipopt's options; the cold solve after it is a fresh session's.
  const fesd::MpccReport fresh =
      fesd::MpccSolver().solve(corner.cut.nlp, corner.solution.solution, 1e-4);
  EXPECT_EQ(cold.iterations, fresh.iterations);
  EXPECT_EQ(cold.solution, fresh.solution);
  // The same through a warm start's polishing (a graze round's branch NLP): a report without
  // multipliers, against the same polish started cold.
  fesd::MpccReport plan;
  plan.solution = corner.solution.solution;
  plan.polish_sigma = corner.solution.polish_sigma;
  fesd::HomotopyOptions always_cold;
  always_cold.ipopt.near_solution_violation = -1.0;
  const fesd::MpccReport polished = solver.solve(corner.cut.nlp, plan, 1e-4);
  const fesd::MpccReport polished_cold =
      fesd::MpccSolver(always_cold).solve(corner.cut.nlp, plan, 1e-4);
  for (const fesd::MpccReport* report : {&polished, &polished_cold}) {
    ASSERT_EQ(report->status, fesd::SolveStatus::kSuccess) << report->message;
    EXPECT_TRUE(report->polished);
    // Inside the row by Ipopt's last mu over the row's multiplier (2e-4).
    EXPECT_NEAR(report->solution[corner.cut.x], 1.0 - 1e-4, 1e-6);
  }
  EXPECT_LT(polished.iterations, polished_cold.iterations)
      << polished.iterations << " against " << polished_cold.iterations;
}

TEST(MpccSolver, AFirstRelaxationAtItsIterationLimitStartsOverOnceLooser) {
  CornerMpcc problem, same_problem;
  fesd::HomotopyOptions options;
  options.sigma_initial = 1e-2;
  options.ipopt.max_iterations = 1;  // every relaxed NLP stops at the limit
  options.max_steps = 3;
  const fesd::MpccReport plain = problem.solve(options);
  ASSERT_GE(plain.history.size(), 2u);
  EXPECT_EQ(plain.history[0].ipopt_status, "maximum_iterations_exceeded");
  EXPECT_DOUBLE_EQ(plain.history[1].sigma, 1e-3);
  options.loosen_failed_first_relaxation = true;
  const fesd::MpccReport loosened = same_problem.solve(options);
  ASSERT_GE(loosened.history.size(), 3u);
  // The first NLP again, from the same start at sigma / kappa; then the homotopy goes on (only
  // once: the loosened one failed too).
  EXPECT_DOUBLE_EQ(loosened.history[0].sigma, 1e-2);
  EXPECT_DOUBLE_EQ(loosened.history[1].sigma, 1e-1);
  EXPECT_DOUBLE_EQ(loosened.history[2].sigma, 1e-2);
  EXPECT_EQ(loosened.history[1].iterations, plain.history[0].iterations);
}

TEST(MpccSolver, AFirstRelaxationThatMayStartOverStopsAtItsOwnCap) {
  fesd::HomotopyOptions options;
  options.sigma_initial = 1e-2;
  options.first_relaxation_iterations = 1;
  CornerMpcc problem, loosening;
  const fesd::MpccReport plain = problem.solve(options);  // no start over: no cap either
  ASSERT_EQ(plain.status, fesd::SolveStatus::kSuccess) << plain.message;
  EXPECT_GT(plain.history[0].iterations, 1);
  EXPECT_TRUE(plain.history[0].converged);
  options.loosen_failed_first_relaxation = true;
  const fesd::MpccReport report = loosening.solve(options);
  ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess) << report.message;
  ASSERT_GE(report.history.size(), 3u);
  EXPECT_EQ(report.history[0].iterations, 1);
  EXPECT_EQ(report.history[0].ipopt_status, "maximum_iterations_exceeded");
  // The loosened start and everything after it have Ipopt's own cap.
  EXPECT_DOUBLE_EQ(report.history[1].sigma, 1e-1);
  EXPECT_TRUE(report.history[1].converged);
  EXPECT_NEAR(report.solution[loosening.x], 1.0, 1e-6);
}

TEST(MpccSolver, APreviousActiveSetsPolishStopsAtItsOwnIterationCap) {
  CutCorner corner(1e-4);
  ASSERT_EQ(corner.solution.status, fesd::SolveStatus::kSuccess) << corner.solution.message;
  fesd::MpccReport plan;
  plan.solution = corner.solution.solution;
  plan.polish_sigma = corner.solution.polish_sigma;
  const fesd::MpccReport uncapped = fesd::MpccSolver().solve(corner.cut.nlp, plan, 1e-4);
  ASSERT_EQ(uncapped.status, fesd::SolveStatus::kSuccess) << uncapped.message;
  ASSERT_TRUE(uncapped.polished);
  ASSERT_GT(uncapped.history.front().iterations, 1);
  // Capped at one iteration the polish stops unconverged, and the homotopy solves the MPCC.
  fesd::HomotopyOptions capped;
  capped.previous_polish_iterations = 1;
  const fesd::MpccReport report = fesd::MpccSolver(capped).solve(corner.cut.nlp, plan, 1e-4);
  ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess) << report.message;
  EXPECT_EQ(report.history.front().sigma, 0.0);
  EXPECT_EQ(report.history.front().iterations, 1);
  EXPECT_FALSE(report.history.front().converged);
  EXPECT_NEAR(report.solution[corner.cut.x], 1.0 - 1e-4, 1e-6);
}

// The polish after the homotopy stops at polish_iterations too: a branch NLP that does not fit
// its active set ran to Ipopt's limit of 500, three attempts at a time (cluttered seed 114).
TEST(MpccSolver, TheLastRelaxationsPolishStopsAtThePolishCap) {
  const auto polishes = [](const fesd::MpccReport& report) {
    std::vector<fesd::HomotopyStep> steps;
    for (const fesd::HomotopyStep& step : report.history) {
      if (step.sigma == 0.0) steps.push_back(step);
    }
    return steps;
  };
  CutCorner corner(1e-4);
  fesd::HomotopyOptions one_relaxation;
  one_relaxation.sigma_initial = 1e-5;
  one_relaxation.max_steps = 1;
  const fesd::MpccReport uncapped =
      fesd::MpccSolver(one_relaxation).solve(corner.cut.nlp, {1.0, 0.5});
  ASSERT_EQ(uncapped.status, fesd::SolveStatus::kSuccess) << uncapped.message;
  ASSERT_EQ(polishes(uncapped).size(), 1u);
  ASSERT_GT(polishes(uncapped).front().iterations, 1);
  fesd::HomotopyOptions capped = one_relaxation;
  capped.polish_iterations = 1;
  const fesd::MpccReport report = fesd::MpccSolver(capped).solve(corner.cut.nlp, {1.0, 0.5});
  ASSERT_FALSE(polishes(report).empty());
  for (const fesd::HomotopyStep& polish : polishes(report)) {
    EXPECT_EQ(polish.iterations, 1);
    EXPECT_FALSE(polish.converged);
  }
  // One relaxation at 1e-5 and no polish to tolerance: the solve says so.
  EXPECT_EQ(report.status, fesd::SolveStatus::kComplementarityNotMet) << report.message;
}

/// Records the first point evaluated after each change of the relaxation: where each NLP of a
/// solve starts (Ipopt's starting point, after its push off the bounds).
struct StartRecordingAssembly : fesd::NlpAssembly {
  mutable std::vector<std::pair<double, std::vector<double>>> starts;  ///< (sigma, point)
  mutable bool armed = false;
  void setRelaxation(double sigma) override {
    NlpAssembly::setRelaxation(sigma);
    armed = true;
  }
  double objective(const double* x) const override {
    if (armed) starts.push_back({relaxation(), std::vector<double>(x, x + numVariables())});
    armed = false;
    return NlpAssembly::objective(x);
  }
};

/// y where the first relaxed NLP after the unsolved polish of solveCutCornerAfterAnUnsolvedPolish
/// starts, and the solve's report.
std::pair<double, fesd::MpccReport> resumedAfterAnUnsolvedPolish(bool resume) {
  fesd_test::CornerMpcc<StartRecordingAssembly> corner;
  const fesd::MpccReport report = fesd_test::solveCutCornerAfterAnUnsolvedPolish(corner, resume);
  double start_y = std::numeric_limits<double>::quiet_NaN();
  for (const auto& [sigma, point] : corner.nlp.starts) {
    if (sigma == 1e-4) {
      start_y = point[corner.y];
      break;
    }
  }
  return {start_y, report};
}

TEST(MpccSolver, AnUnsolvedPolishOfAPlanHandsItsIterateToTheHomotopyWhereAsked) {
  const auto [plan_start_y, from_plan] = resumedAfterAnUnsolvedPolish(false);
  const auto [polish_start_y, from_polish] = resumedAfterAnUnsolvedPolish(true);
  for (const fesd::MpccReport* report : {&from_plan, &from_polish}) {
    ASSERT_EQ(report->status, fesd::SolveStatus::kSuccess) << report->message;
    ASSERT_FALSE(report->history.empty());
    EXPECT_EQ(report->history.front().iterations, 1);  // the polish, capped
    EXPECT_FALSE(report->history.front().converged);
    EXPECT_NEAR(report->solution[0], 1.0 - 1e-4, 1e-6);
    EXPECT_NEAR(report->solution[1], 0.0, 1e-6);
  }
  // From the plan, its y = 0.3; from the polish's iterate, y held at 0 (pushed off its bound).
  EXPECT_NEAR(plan_start_y, 0.3, 1e-9);
  EXPECT_LT(polish_start_y, 1e-3);
}

TEST(MpccSolver, AStartFarFromFeasibleIsStartedCold) {
  // Cut by 0.5: far more than near_solution_violation, so Ipopt starts as from any guess.
  CutCorner corner(0.5);
  fesd::HomotopyOptions unbounded;
  unbounded.ipopt.added_rows_mu_max = 0.0;
  fesd::MpccSolver solver(unbounded);
  ASSERT_LT(solver.options().ipopt.near_solution_violation, 0.5);
  const fesd::MpccReport near =
      solver.solveNearSolution(corner.cut.nlp, corner.solution.solution, 1e-4, -1.0);
  const fesd::MpccReport cold = solver.solve(corner.cut.nlp, corner.solution.solution, 1e-4);
  ASSERT_EQ(near.status, fesd::SolveStatus::kSuccess) << near.message;
  EXPECT_EQ(near.iterations, cold.iterations);
  EXPECT_EQ(near.solution, cold.solution);
  EXPECT_NEAR(near.solution[corner.cut.x], 0.5, 1e-8);
  // With the barrier bounded (the default; its own Ipopt application) the same solution, and a
  // cold start after it in the same solver is again Ipopt's own: its bound does not carry over.
  fesd::MpccSolver bounded_solver;
  ASSERT_GT(bounded_solver.options().ipopt.added_rows_mu_max, 0.0);
  const fesd::MpccReport bounded =
      bounded_solver.solveNearSolution(corner.cut.nlp, corner.solution.solution, 1e-4, -1.0);
  ASSERT_EQ(bounded.status, fesd::SolveStatus::kSuccess) << bounded.message;
  EXPECT_NEAR(bounded.solution[corner.cut.x], 0.5, 1e-8);
  const fesd::MpccReport cold_after =
      bounded_solver.solve(corner.cut.nlp, corner.solution.solution, 1e-4);
  EXPECT_EQ(cold_after.iterations, cold.iterations);
  EXPECT_EQ(cold_after.solution, cold.solution);
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
  options.max_consecutive_failures = 1;
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

/// min (x-1)^2 + (y+1)^2  s.t.  0 <= x _|_ y >= 0, warm-started at the origin: its active set
/// (x = 0, no pair left biactive) is polished to the origin itself, objective 2, which is not
/// B-stationary. The LPEC
/// there proposes the branch y = 0, whose NLP ends at (1, 0), objective 1, where the next LPEC
/// certifies it: two branch NLPs and two LPECs, no relaxed NLP.
TEST(MpccSolver, PhaseTwoLeavesABranchThatIsNotBStationaryForABetterOne) {
  CornerMpcc corner(-1.0);
  corner.nlp.finalize();
  fesd::NlpAssembly& nlp = corner.nlp;
  const int x = corner.x, y = corner.y;
  fesd::MpccReport origin;
  origin.solution = {0.0, 0.0};
  fesd::HomotopyOptions options;
  options.method = fesd::MpccMethod::kActiveSet;
  options.polish_biactive_fraction = 0.0;  // the origin's pair gets a fixed side, not both free
  const fesd::MpccReport report = fesd::MpccSolver(options).solve(nlp, origin, 1e-2);
  ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess) << report.message;
  EXPECT_TRUE(report.certified) << report.message;
  EXPECT_TRUE(report.b_stationary);
  EXPECT_EQ(report.relaxedNlps(), 0);
  EXPECT_EQ(report.branch_nlps, 2);
  EXPECT_EQ(report.lpecs, 2);
  EXPECT_NEAR(report.objective, 1.0, 1e-9);
  EXPECT_NEAR(report.solution[x], 1.0, 1e-8);
  EXPECT_EQ(report.solution[y], 0.0);
  EXPECT_NEAR(report.lpec_value, 0.0, 1e-12);

  // The homotopy's method rejects the origin by its multipliers and its other branch, and goes
  // on with relaxed NLPs; its answer carries the LPEC's certificate too.
  options.method = fesd::MpccMethod::kHomotopy;
  const fesd::MpccReport homotopy = fesd::MpccSolver(options).solve(nlp, origin, 1e-2);
  ASSERT_EQ(homotopy.status, fesd::SolveStatus::kSuccess) << homotopy.message;
  EXPECT_TRUE(homotopy.certified) << homotopy.message;
  EXPECT_GT(homotopy.relaxedNlps(), 0);
  EXPECT_NEAR(homotopy.objective, 1.0, 1e-8);
}

/// A warm start from the solution of the same problem is that solution, without an Ipopt iteration;
/// from the solution of a changed one (its target moved), Ipopt polishes as before.
TEST(MpccSolver, AWarmStartThatAlreadySolvesTheProblemTakesNoIteration) {
  CornerMpcc corner;
  const fesd::MpccReport cold = corner.solve();
  ASSERT_EQ(cold.status, fesd::SolveStatus::kSuccess) << cold.message;
  fesd::MpccSolver solver;
  const fesd::MpccReport again = solver.solve(corner.nlp, cold, 1e-2);
  ASSERT_EQ(again.status, fesd::SolveStatus::kSuccess) << again.message;
  EXPECT_EQ(again.iterations, 0);
  EXPECT_EQ(again.solution, cold.solution);
  EXPECT_TRUE(again.certified) << again.certificate;
  fesd::MpccReport moved = cold;
  moved.solution[corner.x] += 1e-3;  // no longer a KKT point of its branch
  const fesd::MpccReport polished = solver.solve(corner.nlp, moved, 1e-2);
  ASSERT_EQ(polished.status, fesd::SolveStatus::kSuccess) << polished.message;
  EXPECT_GT(polished.iterations, 0);
  EXPECT_NEAR(polished.solution[corner.x], 1.0, 1e-8);
}

TEST(MpccSolver, MethodsHaveNames) {
  fesd::MpccMethod method = fesd::MpccMethod::kHomotopy;
  ASSERT_TRUE(fesd::parseMethod("active_set", method));
  EXPECT_EQ(method, fesd::MpccMethod::kActiveSet);
  EXPECT_EQ(fesd::methodName(method), "active_set");
  ASSERT_TRUE(fesd::parseMethod("homotopy", method));
  EXPECT_EQ(fesd::methodName(method), "homotopy");
  EXPECT_FALSE(fesd::parseMethod("newton", method));
  EXPECT_EQ(method, fesd::MpccMethod::kHomotopy);
}
