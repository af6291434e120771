// More switches in one interval than its elements can hold. Such a solution
// must say so (Trajectory::unresolved_switches, the message); a resolved one must not.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/circle_example.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/ocp/ocp_solver.h"

namespace {

namespace example = fesd::circle_example;

/// Pozharskiy et al. 2024 Example 1 as an OCP without controls on a single control interval, which
/// then has to hold both switches (contact at 5 pi / 12, release sqrt 3 later) in `elements`
/// elements.
fesd::OcpSolution solveCircleInOneInterval(int elements, bool fesd_on) {
  fesd::OcpDefinition ocp;
  ocp.model = example::model();
  ocp.initial_state = example::initialState();
  ocp.horizon = example::horizon();
  ocp.num_intervals = 1;
  fesd::OcpOptions options;
  options.discretization.num_stages = 2;
  options.discretization.num_elements = elements;
  options.discretization.switch_detection = fesd_on;
  fesd::OcpSolver solver(ocp, options);
  return solver.solve();
}

double terminalError(const fesd::Trajectory& trajectory) {
  return (trajectory.finalState() - example::exactState(example::horizon())).norm();
}

bool containsASwitchTime(const fesd::UnresolvedSwitch& element) {
  for (double t : {example::contactTime(), example::releaseTime()}) {
    if (element.start_time < t && t < element.end_time) return true;
  }
  return false;
}

TEST(UnresolvedSwitches, TooFewElementsAreNeverAFullAccuracySuccess) {
  // One element cannot hold two switches: FESD's polynomial steps over the contact (c < 0
  // between stage points that satisfy it). With two elements, one boundary for two switches,
  // the MPCC has no solution.
  for (int elements : {1, 2}) {
    const fesd::OcpSolution solution = solveCircleInOneInterval(elements, true);
    EXPECT_GT(terminalError(solution.trajectory), 0.1);  // the solution is indeed wrong
    EXPECT_FALSE(solution.status == fesd::SolveStatus::kSuccess &&
                 solution.trajectory.switchesResolved())
        << elements << " element(s): " << solution.message;
    for (const Eigen::VectorXd& x : solution.trajectory.states) EXPECT_TRUE(x.allFinite());
  }
  const fesd::OcpSolution one = solveCircleInOneInterval(1, true);
  ASSERT_EQ(one.trajectory.unresolved_switches.size(), 1u) << one.message;
  EXPECT_TRUE(one.trajectory.unresolved_switches[0].passes_through);
  EXPECT_NEAR(one.trajectory.elements[0].lowest_constraints(0), -0.09, 0.02);
  EXPECT_NE(one.message.find("unresolved switch"), std::string::npos) << one.message;
}

TEST(UnresolvedSwitches, TheStandardMethodSwitchesInsideElementsAndIsFlaggedThere) {
  const fesd::OcpSolution solution = solveCircleInOneInterval(4, false);
  ASSERT_EQ(solution.status, fesd::SolveStatus::kSuccess) << solution.message;
  EXPECT_GT(terminalError(solution.trajectory), 0.05);
  // Exactly the two elements that contain the analytic contact and release times.
  ASSERT_EQ(solution.trajectory.unresolved_switches.size(), 2u) << solution.message;
  for (const fesd::UnresolvedSwitch& element : solution.trajectory.unresolved_switches) {
    EXPECT_TRUE(containsASwitchTime(element))
        << "[" << element.start_time << ", " << element.end_time << "]";
  }
  EXPECT_NE(solution.message.find("unresolved switch"), std::string::npos);
}

TEST(UnresolvedSwitches, EnoughElementsResolveBothSwitchesAndAreNotFlagged) {
  const fesd::OcpSolution solution = solveCircleInOneInterval(3, true);
  ASSERT_EQ(solution.status, fesd::SolveStatus::kSuccess) << solution.message;
  EXPECT_TRUE(solution.trajectory.switchesResolved()) << solution.message;
  EXPECT_EQ(solution.message.find("unresolved"), std::string::npos);
  ASSERT_EQ(solution.trajectory.switches.size(), 2u);
  EXPECT_NEAR(solution.trajectory.switches[0].time, example::contactTime(), 0.05);
  EXPECT_NEAR(solution.trajectory.switches[1].time, example::releaseTime(), 0.05);

  // The simulation on a fine grid: accurate to 1e-8 and nothing flagged.
  fesd::SimulationOptions options;
  options.discretization.num_stages = 4;
  fesd::FesdIntegrator integrator(example::model(), options);
  const fesd::SimulationResult fine =
      integrator.simulate(example::initialState(), example::horizon(), 10);
  ASSERT_EQ(fine.status, fesd::SolveStatus::kSuccess) << fine.message;
  EXPECT_LT(terminalError(fine.trajectory), 1e-8);
  EXPECT_TRUE(fine.trajectory.switchesResolved()) << fine.message;
}

}  // namespace
