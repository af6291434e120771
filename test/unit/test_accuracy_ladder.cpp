// The accuracy ladder (planning/accuracy_ladder.cpp): its bookkeeping on scripted rungs, and what
// the next rung refines for a blamed plan.
#include <gtest/gtest.h>

#include <limits>
#include <string>
#include <vector>

#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "support/scene_tasks.h"

namespace {

using fesd::SolveStatus;

fesd::AccuracyRung rung(SolveStatus status, double error, int grazes = 0) {
  fesd::AccuracyRung r;
  r.stages = 2;
  r.interval_elements = {3, 3};
  r.status = status;
  r.verification_error = error;
  r.grazes = grazes;
  return r;
}

TEST(AccuracyLadder, MeetsTheTargetOnlyAccurateAndWithoutGrazes) {
  fesd::AccuracyLadder ladder(1e-2, 100.0);
  EXPECT_TRUE(ladder.record(rung(SolveStatus::kSuccess, 4e-2)));
  EXPECT_FALSE(ladder.finished());
  EXPECT_TRUE(ladder.record(rung(SolveStatus::kSuccess, 1e-3, 1)));  // more accurate, grazing
  EXPECT_FALSE(ladder.finished());
  EXPECT_TRUE(ladder.record(rung(SolveStatus::kTargetNotReached, 6e-3)));
  EXPECT_TRUE(ladder.finished());
  EXPECT_EQ(ladder.finalStatus(SolveStatus::kTargetNotReached), SolveStatus::kTargetNotReached);
  EXPECT_EQ(ladder.summary().rfind("accuracy target 0.01 met on rung 3 (n_s = 2, N_FE = 3)", 0), 0u)
      << ladder.summary();
}

TEST(AccuracyLadder, AnInaccurateLadderAnswersItsMostAccurateSolution) {
  fesd::AccuracyLadder ladder(1e-3, 100.0);
  ladder.record(rung(SolveStatus::kSuccess, 5e-2));
  ladder.record(rung(SolveStatus::kSuccess, 2e-2));
  EXPECT_FALSE(ladder.record(rung(SolveStatus::kMaxIterations, 1e-9)));  // a failure never counts
  EXPECT_FALSE(ladder.record(rung(SolveStatus::kSuccess, 3e-2)));
  ladder.end();
  EXPECT_TRUE(ladder.finished());
  EXPECT_EQ(ladder.finalStatus(SolveStatus::kSuccess), SolveStatus::kAccuracyNotMet);
  EXPECT_NE(ladder.summary().find("not met: best verification error 0.02 (rung 2 of 4, the "
                                  "ladder ended)"),
            std::string::npos)
      << ladder.summary();
}

TEST(AccuracyLadder, AFailedFirstRungKeepsItsStatus) {
  fesd::AccuracyLadder ladder(1e-3, 100.0);
  EXPECT_TRUE(ladder.record(rung(SolveStatus::kMaxIterations, 1.0)));
  ladder.end();
  EXPECT_EQ(ladder.finalStatus(SolveStatus::kMaxIterations), SolveStatus::kMaxIterations);
}

TEST(AccuracyLadder, ASpentBudgetOrACancelStopsTheClimb) {
  fesd::AccuracyLadder spent(1e-3, 0.0);
  spent.record(rung(SolveStatus::kSuccess, 1.0));
  EXPECT_TRUE(spent.finished());
  EXPECT_EQ(spent.finalStatus(SolveStatus::kSuccess), SolveStatus::kTimeout);
  EXPECT_NE(spent.summary().find("the wall-time budget spent"), std::string::npos);
  fesd::AccuracyLadder cancelled(1e-3, 100.0);
  cancelled.record(rung(SolveStatus::kSuccess, 1.0));
  EXPECT_FALSE(cancelled.record(rung(SolveStatus::kCancelled, 1e-9)));
  EXPECT_TRUE(cancelled.finished());
  EXPECT_EQ(cancelled.finalStatus(SolveStatus::kSuccess), SolveStatus::kCancelled);
}

TEST(AccuracyLadder, AnUnverifiedRungNeverMeetsTheTarget) {
  fesd::AccuracyLadder ladder(1e-3, 100.0);
  ladder.record(rung(SolveStatus::kSuccess, std::numeric_limits<double>::quiet_NaN()));
  EXPECT_FALSE(ladder.finished());
  EXPECT_TRUE(ladder.record(rung(SolveStatus::kSuccess, 1e-4)));
  EXPECT_TRUE(ladder.finished());
}

/// A plan of 4 intervals of 3 elements of pushingTask (pusher/puck is pair 0 of its decisions)
/// with a contact at the start of element 7 (interval 2, resolved) and one inside element 4
/// (interval 1, unresolved), verified with the given interval errors.
fesd::SceneOutcome blamedPlan(const fesd::SceneTask& task, const std::vector<double>& errors) {
  fesd::SceneOutcome outcome;
  outcome.decisions = fesd::decidePairs(task);
  for (int e = 0; e < 12; ++e) {
    fesd::ElementValues element;
    element.interval = e / 3;
    outcome.trajectory.elements.push_back(element);
  }
  outcome.trajectory.switches.push_back({1.2, 0, fesd::SwitchEvent::Kind::kContact, 7});
  outcome.trajectory.unresolved_switches.push_back({4, 1, 0, 0.6, 0.8, false});
  outcome.verified = true;
  outcome.verification.status = SolveStatus::kSuccess;
  outcome.verification.interval_errors = errors;
  outcome.verification.error = *std::max_element(errors.begin(), errors.end());
  return outcome;
}

TEST(NextRung, MoreElementsWhereASwitchIsUnresolvedAStageMoreWhereTheErrorIsSmooth) {
  const fesd::SceneTask task = fesd_test::pushingTask();
  const fesd::TaskLimits limits;  // 4 stages, 6 elements
  const std::vector<int> three(4, 3);
  // Interval 1 holds the unresolved switch: more elements there, nothing else.
  const fesd::RungChange inside = fesd::nextRung(task, blamedPlan(task, {1e-3, 5e-2, 1e-3, 1e-4}),
                                                 2, three, limits, 1e-2, 1e-6);
  EXPECT_FALSE(inside.none);
  EXPECT_EQ(inside.interval_elements, (std::vector<int>{3, 6, 3, 3}));
  EXPECT_EQ(inside.stages, 2);
  EXPECT_EQ(inside.refined_intervals, std::vector<int>{1});
  EXPECT_EQ(inside.change, "more elements in intervals 1");
  EXPECT_NE(inside.reason.find("at switches inside elements"), std::string::npos);
  EXPECT_EQ(inside.error_before, 5e-2);
  // Interval 2's switch is resolved: its error is smooth, as interval 3's: a stage more.
  const fesd::RungChange smooth = fesd::nextRung(task, blamedPlan(task, {1e-3, 1e-3, 3e-2, 2e-2}),
                                                 2, three, limits, 1e-2, 1e-6);
  EXPECT_EQ(smooth.stages, 3);
  EXPECT_EQ(smooth.interval_elements, three);
  EXPECT_EQ(smooth.change, "n_s 2 -> 3");
  EXPECT_EQ(smooth.refined_intervals, (std::vector<int>{2, 3}));
  EXPECT_NE(smooth.reason.find("smooth intervals 2-3"), std::string::npos) << smooth.reason;
  // Both: elements in interval 1 and a stage more.
  const fesd::RungChange both = fesd::nextRung(task, blamedPlan(task, {1e-3, 5e-2, 3e-2, 1e-4}), 2,
                                               three, limits, 1e-2, 1e-6);
  EXPECT_EQ(both.change, "more elements in intervals 1; n_s 2 -> 3");
  EXPECT_EQ(both.interval_elements, (std::vector<int>{3, 6, 3, 3}));
  EXPECT_EQ(both.stages, 3);
  // At the most stages: more elements in the smooth intervals, up to the limit.
  const fesd::RungChange no_more_stages = fesd::nextRung(
      task, blamedPlan(task, {1e-3, 1e-3, 3e-2, 2e-2}), 4, {3, 3, 4, 6}, limits, 1e-2, 1e-6);
  EXPECT_EQ(no_more_stages.interval_elements, (std::vector<int>{3, 3, 6, 6}));
  EXPECT_EQ(no_more_stages.refined_intervals, std::vector<int>{2});
  // Nothing above the target and no graze: nothing to refine.
  EXPECT_TRUE(
      fesd::nextRung(task, blamedPlan(task, {1e-3, 1e-3, 1e-3, 1e-3}), 2, three, limits, 1e-2, 1e-6)
          .none);
}

TEST(NextRung, HoldsTheGrazesThePlanCutsInto) {
  const fesd::SceneTask task = fesd_test::pushingTask();
  fesd::SceneOutcome outcome = blamedPlan(task, {1e-3, 1e-3, 1e-3, 1e-3});
  fesd::Graze cut;
  cut.pair = outcome.decisions[0].pair;
  cut.interval = 2;
  cut.depth = -1e-4;
  fesd::Graze touch = cut;  // a touch the plan clears: reported, not held
  touch.interval = 3;
  touch.depth = 1e-9;
  outcome.verification.grazes = {cut, touch};
  const fesd::RungChange held =
      fesd::nextRung(task, outcome, 2, std::vector<int>(4, 3), fesd::TaskLimits{}, 1e-2, 1e-6);
  EXPECT_FALSE(held.none);
  ASSERT_EQ(held.held_grazes.size(), 1u);
  EXPECT_EQ(held.held_grazes[0].interval, 2);
  EXPECT_EQ(held.change, "grazes held in intervals 2");
  EXPECT_EQ(held.interval_elements, std::vector<int>(4, 3));
  // Already held: nothing new to do.
  outcome.held_grazes = held.held_grazes;
  EXPECT_TRUE(
      fesd::nextRung(task, outcome, 2, std::vector<int>(4, 3), fesd::TaskLimits{}, 1e-2, 1e-6)
          .none);
}

}  // namespace
