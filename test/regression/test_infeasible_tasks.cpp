// An OCP whose terminal constraint cannot be reached ends with a non-success
// status and a message, never with SUCCESS; with a reachable bound the same structure solves.
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/function/affine_function.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "support/scene_tasks.h"

namespace {

using fesd_test::slowPushingTask;

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
