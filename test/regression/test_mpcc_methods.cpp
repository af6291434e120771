// The active-set method (relaxed NLPs only until a branch NLP solves, then LPECs) against the
// homotopy on scenes where both find the same branch: the same plan in fewer relaxed NLPs, and
// every answer certified B-stationary by its LPEC.
#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/examples/planning_scenes.h"
#include "fesd_trajopt/planning/scene_solver.h"

namespace {

fesd::SceneOutcome solveBy(const fesd::SceneTask& task, fesd::MpccMethod method) {
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 3;
  options.ocp.homotopy.method = method;
  return fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
}

void expectSamePlanInFewerNlps(const fesd::SceneTask& task) {
  const fesd::SceneOutcome homotopy = solveBy(task, fesd::MpccMethod::kHomotopy);
  const fesd::SceneOutcome active_set = solveBy(task, fesd::MpccMethod::kActiveSet);
  ASSERT_EQ(homotopy.status, fesd::SolveStatus::kSuccess) << homotopy.message;
  ASSERT_EQ(active_set.status, fesd::SolveStatus::kSuccess) << active_set.message;
  EXPECT_TRUE(homotopy.report.certified) << homotopy.report.certificate;
  EXPECT_TRUE(active_set.report.certified) << active_set.report.certificate;
  EXPECT_GE(active_set.report.lpecs, 1);
  // The branch NLP keeps the regulariser the homotopy polishes with: the same objective.
  EXPECT_NEAR(active_set.report.objective, homotopy.report.objective,
              1e-8 * homotopy.report.objective);
  EXPECT_LT(active_set.report.relaxedNlps(), homotopy.report.relaxedNlps());
  EXPECT_LE(active_set.report.iterations, homotopy.report.iterations);
  EXPECT_EQ(active_set.trajectory.switches.size(), homotopy.trajectory.switches.size());
  for (size_t k = 0; k < homotopy.trajectory.switches.size(); ++k) {
    EXPECT_NEAR(active_set.trajectory.switches[k].time, homotopy.trajectory.switches[k].time, 1e-6);
  }
}

TEST(MpccMethods, TheShowcaseEndsOnTheSamePlanInFewerRelaxedNlps) {
  expectSamePlanInFewerNlps(fesd::manipulation_example::task(40));
}

TEST(MpccMethods, APushAlongAWallEndsOnTheSamePlanInFewerRelaxedNlps) {
  expectSamePlanInFewerNlps(fesd::planning_scenes::scene("wall", 1).task);
}

}  // namespace
