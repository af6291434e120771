// Issue 6 case 10: problems that cannot be solved (targets outside the workspace or out of
// reach, contradictory bounds, unreachable terminal constraints) end with a non-success status
// and a message, never with SUCCESS.
#include <gtest/gtest.h>

#include "fesd_trajopt/function/affine_function.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/scene/scene_task.h"

namespace {

/// A pusher (R = 0.5) at (-3, 0) with |u| <= 1 per coordinate, a puck at the origin, T = 2:
/// both can get at most D = T sqrt(2) = 2.83 from their starts.
fesd::SceneTask slowPushingTask() {
  fesd::SceneTask task;
  task.scene.bodies() = {{"pusher", 0.5, Eigen::Vector2d(-3.0, 0.0), true},
                         {"puck", 0.5, Eigen::Vector2d(0.0, 0.0), false},
                         {"rock", 0.5, Eigen::Vector2d(50.0, 0.0), false}};
  task.bodies.resize(3);
  task.bodies[0].max_speed = 1.0;
  task.horizon = 2.0;
  task.num_intervals = 4;
  return task;
}

std::string infeasibility(void (*change)(fesd::SceneTask&)) {
  fesd::SceneTask task = slowPushingTask();
  change(task);
  EXPECT_EQ(fesd::validateTask(task, fesd::TaskLimits{}), "");  // well-formed, just impossible
  return fesd::infeasibility(task);
}

TEST(InfeasibleTasks, TargetsOutsideTheWorkspaceOrOutOfReachAreNamed) {
  EXPECT_EQ(infeasibility([](fesd::SceneTask& t) {
              t.bodies[1].target = Eigen::Vector2d(1.5, 0.0);
              t.bodies[1].target_weight = 1.0;
            }),
            "");
  EXPECT_EQ(infeasibility([](fesd::SceneTask& t) {
              t.bodies[1].target = Eigen::Vector2d(1.5, 0.0);
              t.bodies[1].target_weight = 1.0;
              t.bodies[1].workspace_upper = Eigen::Vector2d(1.0, 5.0);
            }),
            "body 'puck' has its target outside its workspace bounds");
  // The pusher's box ends at x = -3 + 2.83 = -0.17: it misses (10, 0) by 10.2.
  EXPECT_EQ(infeasibility([](fesd::SceneTask& t) {
              t.bodies[0].target = Eigen::Vector2d(10.0, 0.0);
              t.bodies[0].target_weight = 1.0;
            }),
            "body 'pusher' cannot reach its target within the horizon: it stays at least 10.2 "
            "away");
  EXPECT_EQ(infeasibility([](fesd::SceneTask& t) {
              t.bodies[2].target = Eigen::Vector2d(51.0, 0.0);
              t.bodies[2].target_weight = 1.0;
            }),
            "body 'rock' cannot reach its target within the horizon: it stays at least 1 away "
            "(nothing that moves can push it)");
  // A target without weight is no goal.
  EXPECT_EQ(infeasibility([](fesd::SceneTask& t) { t.bodies[0].target = Eigen::Vector2d(9, 9); }),
            "");
}

TEST(InfeasibleTasks, ContradictoryBoundsAreRefusedByValidation) {
  fesd::SceneTask task = slowPushingTask();
  task.bodies[1].workspace_lower = Eigen::Vector2d(-1.0, -1.0);
  task.bodies[1].workspace_upper = Eigen::Vector2d(1.0, -2.0);
  EXPECT_EQ(fesd::validateTask(task, fesd::TaskLimits{}),
            "body 'puck': the workspace bounds are contradictory (lower > upper)");
}

/// A pushing task's OCP with the terminal constraint  x_puck(T) >= reach_x.
fesd::OcpDefinition unreachableTerminalOcp(const fesd::SceneTask& task, double reach_x) {
  std::vector<fesd::ContactPair> pairs;
  for (const fesd::PairDecision& d : fesd::decidePairs(task)) {
    if (d.modelled) pairs.push_back(d.pair);
  }
  fesd::OcpDefinition ocp = fesd::buildOcp(task, pairs);
  Eigen::SparseMatrix<double> minus_puck_x(1, task.scene.stateSize());
  minus_puck_x.insert(0, task.scene.stateIndex(1)) = -1.0;
  ocp.terminal_constraints = std::make_shared<fesd::AffineFunction>(
      minus_puck_x, Eigen::VectorXd::Constant(1, reach_x));  // reach_x - x_puck(T) <= 0
  return ocp;
}

TEST(InfeasibleTasks, AnUnreachableTerminalConstraintIsNeverASuccess) {
  // With T = 4 the pusher (1 m/s) reaches the puck at t = 2 and then pushes it at 0.5 m/s
  // (the projection shares the velocity): the puck gets to x = 1 at most.
  fesd::SceneTask task = slowPushingTask();
  task.horizon = 4.0;
  fesd::OcpOptions options;
  options.homotopy.max_steps = 6;  // every relaxed NLP is infeasible: no need to go far
  const fesd::OcpSolution impossible =
      fesd::OcpSolver(unreachableTerminalOcp(task, 3.0), options).solve();
  EXPECT_EQ(impossible.status, fesd::SolveStatus::kInfeasible) << impossible.message;
  EXPECT_NE(impossible.message.find("infeasible"), std::string::npos);
  for (const Eigen::VectorXd& x : impossible.trajectory.states) EXPECT_TRUE(x.allFinite());

  // The same structure with a reachable bound solves: the status comes from the problem.
  const fesd::OcpSolution possible =
      fesd::OcpSolver(unreachableTerminalOcp(task, 0.5), options).solve();
  EXPECT_EQ(possible.status, fesd::SolveStatus::kSuccess) << possible.message;
  EXPECT_GE(possible.trajectory.finalState()(2), 0.5 - 1e-8);
}

}  // namespace
