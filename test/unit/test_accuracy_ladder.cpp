// The accuracy ladder's rungs and bookkeeping (planning/accuracy_ladder.cpp), on scripted rungs.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"

namespace {

using fesd::SolveStatus;

/// What the ladder needs of an outcome.
struct ScriptedOutcome {
  SolveStatus status = SolveStatus::kSolverError;
  double verification_error = std::numeric_limits<double>::infinity();
  std::string message;
  std::vector<fesd::AccuracyRung> refinements;
  int stages = 0, elements = 0;
  bool refused = false;
};

struct ScriptedOptions {
  fesd::OcpOptions ocp;
};

/// Climbs from (2, 3) under the default limits (4 stages, 6 elements), answering rung k with
/// script[k] (the last entry repeats).
ScriptedOutcome climb(const std::vector<std::pair<SolveStatus, double>>& script, double target,
                      double budget = 100.0) {
  ScriptedOptions options;
  options.ocp.discretization.num_stages = 2;
  options.ocp.discretization.num_elements = 3;
  options.ocp.homotopy.wall_time_budget = budget;
  size_t rung = 0;
  return fesd::climbAccuracyLadder<ScriptedOutcome>(
      options, fesd::TaskLimits{}, target,
      [&](const ScriptedOptions& o) {
        const auto& [status, error] = script[std::min(rung++, script.size() - 1)];
        ScriptedOutcome outcome;
        outcome.status = status;
        outcome.verification_error = error;
        outcome.message = "solved";
        outcome.stages = o.ocp.discretization.num_stages;
        outcome.elements = o.ocp.discretization.num_elements;
        outcome.refused = status == SolveStatus::kInfeasible;  // a refusal, in this script
        return outcome;
      },
      [](const ScriptedOutcome& outcome) { return outcome.refused; });
}

TEST(AccuracyRungs, MoreStagesFirstThenMoreElements) {
  fesd::TaskLimits limits;
  limits.max_stages = 4;
  limits.max_elements = 5;
  const std::vector<std::pair<int, int>> expected{{2, 3}, {3, 3}, {4, 3}, {4, 4}, {4, 5}};
  EXPECT_EQ(fesd::accuracyRungs(2, 3, limits), expected);
  EXPECT_EQ(fesd::accuracyRungs(4, 5, limits), (std::vector<std::pair<int, int>>{{4, 5}}));
}

TEST(AccuracyLadder, StopsAtTheFirstAccurateRungAndKeepsItsStatus) {
  const ScriptedOutcome met =
      climb({{SolveStatus::kSuccess, 4e-2}, {SolveStatus::kTargetNotReached, 6e-4}}, 1e-2);
  EXPECT_EQ(met.status, SolveStatus::kTargetNotReached);
  EXPECT_EQ(met.verification_error, 6e-4);
  EXPECT_EQ(met.stages, 3);
  ASSERT_EQ(met.refinements.size(), 2u);
  EXPECT_EQ(met.refinements[0].verification_error, 4e-2);
  EXPECT_EQ(met.message.rfind("accuracy target 0.01 met on rung 2 (n_s = 3, N_FE = 3)", 0), 0u)
      << met.message;
  EXPECT_NE(met.message.find("; solved"), std::string::npos);
}

TEST(AccuracyLadder, AnInaccurateLadderAnswersItsMostAccurateSolution) {
  const ScriptedOutcome missed = climb({{SolveStatus::kSuccess, 5e-2},
                                        {SolveStatus::kSuccess, 2e-2},
                                        {SolveStatus::kMaxIterations, 1e-9},
                                        {SolveStatus::kSuccess, 3e-2}},
                                       1e-3);
  // Rungs (2,3) (3,3) (4,3) (4,4) (4,5) (4,6); a failed rung never counts as the best.
  EXPECT_EQ(missed.refinements.size(), 6u);
  EXPECT_EQ(missed.status, SolveStatus::kAccuracyNotMet);
  EXPECT_EQ(missed.verification_error, 2e-2);
  EXPECT_EQ(missed.stages, 3);
  EXPECT_NE(missed.message.find("not met: best verification error 0.02 (of 6 rung(s), the "
                                "ladder ended)"),
            std::string::npos)
      << missed.message;
}

TEST(AccuracyLadder, AFailedFirstRungKeepsItsStatusAndARefusalEndsTheClimb) {
  const ScriptedOutcome failed = climb({{SolveStatus::kMaxIterations, 1.0}}, 1e-3);
  EXPECT_EQ(failed.status, SolveStatus::kMaxIterations);
  const ScriptedOutcome refused = climb({{SolveStatus::kInfeasible, 0.0}}, 1e-3);
  EXPECT_TRUE(refused.refused);
  EXPECT_TRUE(refused.refinements.empty());
}

TEST(AccuracyLadder, ASpentBudgetOrACancelStopsTheClimb) {
  const ScriptedOutcome timed_out = climb({{SolveStatus::kSuccess, 1.0}}, 1e-3, 0.0);
  EXPECT_EQ(timed_out.refinements.size(), 1u);
  EXPECT_EQ(timed_out.status, SolveStatus::kTimeout);
  EXPECT_NE(timed_out.message.find("the wall-time budget spent"), std::string::npos);
  const ScriptedOutcome cancelled =
      climb({{SolveStatus::kSuccess, 1.0}, {SolveStatus::kCancelled, 1e-9}}, 1e-3);
  EXPECT_EQ(cancelled.refinements.size(), 2u);
  EXPECT_EQ(cancelled.status, SolveStatus::kCancelled);
  EXPECT_EQ(cancelled.verification_error, 1.0);  // the cancelled rung's iterate is no solution
}

TEST(AccuracyLadder, AnUnverifiedRungNeverMeetsTheTarget) {
  const ScriptedOutcome unverified =
      climb({{SolveStatus::kSuccess, std::numeric_limits<double>::quiet_NaN()},
             {SolveStatus::kSuccess, 1e-4}},
            1e-3);
  EXPECT_EQ(unverified.status, SolveStatus::kSuccess);
  EXPECT_EQ(unverified.refinements.size(), 2u);
  EXPECT_EQ(unverified.verification_error, 1e-4);
}

}  // namespace
