// Scenes in other length units (scene/scene_units.cpp): the length scale a solve measures a task
// in, a task scaled as a user would rescale it, and the task a solve at a length scale sees, whose
// constraints, costs, bounds and dynamics are the task's in those units.
#include "fesd_trajopt/scene/scene_units.h"

#include <cmath>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/kinematics/model_units.h"
#include "fesd_trajopt/kinematics/reach.h"
#include "support/finite_differences.h"
#include "support/robot_files.h"
#include "support/scene_tasks.h"

namespace {

fesd::SceneTask pandaTask() {
  return fesd::pandaPushTask(std::make_shared<const fesd::KinematicModel>(
      fesd_test::loadShippedRobot("panda_spherized.urdf")));
}

double evaluate(const fesd::SmoothFunction& f, const Eigen::VectorXd& z) {
  double value = 0.0;
  f.evaluate(z.data(), &value);
  return value;
}

TEST(SceneUnits, TheLengthScaleIsTheMedianRadiusOfWhatTheControlsMove) {
  EXPECT_EQ(fesd::lengthScale(fesd::manipulation_example::task(40)), 1.0);  // two of radius 1
  fesd::SceneTask task = fesd_test::boxIntoACorner();  // a pusher of 0.2, a box of 0.25's
  EXPECT_EQ(fesd::lengthScale(task), 0.2);
  task.scene.bodies().push_back({"second", 0.6, Eigen::Vector2d(-3.0, 3.0), true});
  task.bodies.emplace_back();
  EXPECT_DOUBLE_EQ(fesd::lengthScale(task), 0.4);  // the mean of the middle two
  task.scene.bodies()[0].actuated = task.scene.bodies()[2].actuated = false;
  EXPECT_EQ(fesd::lengthScale(task), 0.25);  // nothing actuated: every free body's spheres
  // The robot's spheres on a joint, not its base's: the Panda's are 0.012 to 0.08.
  EXPECT_EQ(fesd::lengthScale(pandaTask()), 0.028);
  // Sizes only: positions, targets and bounds leave it, scaling the task scales it.
  fesd::SceneTask moved = fesd_test::pushAlongX();
  const double before = fesd::lengthScale(moved);
  moved.bodies[1].target *= 3.0;
  moved.scene.bodies()[1].position(1) += 2.0;
  EXPECT_EQ(fesd::lengthScale(moved), before);
  EXPECT_EQ(fesd::lengthScale(fesd::scaledTask(moved, 0.01)), 0.01 * before);
}

TEST(SceneUnits, AScaledTaskHasEveryLengthScaledAndItsAngleWeightsSquared) {
  const fesd::SceneTask task = fesd_test::boxIntoACorner();
  const double k = 0.03;
  const fesd::SceneTask scaled = fesd::scaledTask(task, k);
  const fesd::SceneBody &box = task.scene.bodies()[1], &small = scaled.scene.bodies()[1];
  EXPECT_DOUBLE_EQ(small.radius, k * box.radius);
  EXPECT_LT((small.position - k * box.position).norm(), 1e-15);
  EXPECT_DOUBLE_EQ(small.turning_radius, k * box.turning_radius);
  EXPECT_LT((small.spheres[2].offset - k * box.spheres[2].offset).norm(), 1e-15);
  EXPECT_EQ(small.yaw, box.yaw);
  EXPECT_DOUBLE_EQ(scaled.scene.walls()[0].offset, k * task.scene.walls()[0].offset);
  EXPECT_DOUBLE_EQ(scaled.bodies[0].max_speed, k * task.bodies[0].max_speed);
  EXPECT_LT((scaled.bodies[1].target - k * task.bodies[1].target).norm(), 1e-15);
  EXPECT_EQ(scaled.bodies[1].target_yaw, task.bodies[1].target_yaw);
  EXPECT_DOUBLE_EQ(scaled.bodies[1].target_yaw_weight, k * k * task.bodies[1].target_yaw_weight);
  EXPECT_EQ(scaled.bodies[1].target_weight, task.bodies[1].target_weight);
  EXPECT_EQ(scaled.horizon, task.horizon);
  EXPECT_EQ(scaled.scene.length_unit, 1.0);  // a user's task in other units
  // A robot: its links scaled, its revolute joints' angles and targets kept, their weights
  // squared with the lengths.
  fesd::SceneTask panda = pandaTask();
  panda.joints[0].target = 0.4;
  panda.joints[0].target_weight = 2.0;
  const fesd::SceneTask mm = fesd::scaledTask(panda, 1000.0);
  EXPECT_DOUBLE_EQ(mm.scene.robot().spheres[5].radius,
                   1000.0 * panda.scene.robot().spheres[5].radius);
  EXPECT_EQ(mm.joints[0].target, 0.4);
  EXPECT_DOUBLE_EQ(mm.joints[0].target_weight, 2e6);
  EXPECT_EQ(mm.scene.initialJoints(), panda.scene.initialJoints());
}

// The task in units of L is the task with x -> x / units and u -> u / units (solveUnits: L, a
// revolute joint's L / reach): its pair values are the task's over L^2 (a wall's over L), its
// velocity the task's over the units at the same forces (a wall's over L), the robot's joints
// weighed by the reach squared in the task's, 1 in the solve's; its cost the task's over L^2,
// its bounds over the units.
TEST(SceneUnits, TheTaskInLengthUnitsIsTheTaskOverItsUnits) {
  for (const bool robot : {false, true}) {
    SCOPED_TRACE(robot ? "the Panda" : "a box into a corner");
    fesd::SceneTask task = robot ? pandaTask() : fesd_test::boxIntoACorner();
    if (robot) {
      task.joints[1].target = -0.5;
      task.joints[1].target_weight = 3.0;
    }
    const double length = 0.37;
    const fesd::SceneTask solve = fesd::taskInLengthUnits(task, length);
    EXPECT_EQ(solve.scene.length_unit, length);
    const fesd::SolveUnits units = fesd::solveUnits(solve.scene);
    EXPECT_EQ(units.length, length);
    if (robot) {
      EXPECT_NEAR(fesd::robotReach(solve.scene.robot()), 1.0, 1e-15);
      EXPECT_NEAR(units.state(0), length / fesd::robotReach(task.scene.robot()), 1e-16);
    }
    const std::vector<fesd::ContactPair> pairs = task.scene.allPairs();
    ASSERT_EQ(solve.scene.allPairs().size(), pairs.size());
    const fesd::OcpDefinition ocp = fesd::buildOcp(task, pairs);
    const fesd::OcpDefinition solve_ocp = fesd::buildOcp(solve, pairs);
    const int nx = task.scene.stateSize(), nu = task.scene.controlSize();
    const int nc = static_cast<int>(pairs.size());
    std::mt19937 random(4);
    const Eigen::VectorXd x =
        task.scene.initialState() + 0.05 * fesd_test::randomVector(nx, random);
    const Eigen::VectorXd u = fesd_test::randomVector(nu, random);
    const Eigen::VectorXd lambda = fesd_test::randomVector(nc, random, 0.0, 1.0);
    EXPECT_LT(
        (solve.scene.initialState() - task.scene.initialState().cwiseQuotient(units.state)).norm(),
        1e-12);
    const auto model = task.scene.model(pairs), solve_model = solve.scene.model(pairs);
    Eigen::VectorXd c(nc), solve_c(nc), v(nx), solve_v(nx);
    model->constraints()->evaluate(x.data(), c.data());
    const Eigen::VectorXd x_solve = x.cwiseQuotient(units.state);
    const Eigen::VectorXd u_solve = u.cwiseQuotient(units.control);
    solve_model->constraints()->evaluate(x_solve.data(), solve_c.data());
    Eigen::VectorXd z(nx + nu + nc), solve_z(nx + nu + nc);
    z << x, u, lambda;
    solve_z << x_solve, u_solve, lambda;
    for (int k = 0; k < nc; ++k) {
      const bool wall = pairs[k].kind == fesd::ContactPair::Kind::kWall;
      EXPECT_NEAR(solve_c(k), c(k) / (wall ? length : length * length),
                  1e-12 * (1.0 + std::fabs(solve_c(k))));
      if (wall) solve_z(nx + nu + k) /= length;
    }
    model->velocity()->evaluate(z.data(), v.data());
    solve_model->velocity()->evaluate(solve_z.data(), solve_v.data());
    EXPECT_LT((solve_v - v.cwiseQuotient(units.state)).norm(), 1e-12 * (1.0 + v.norm()));
    Eigen::VectorXd xu(nx + nu), solve_xu(nx + nu);
    xu << x, u;
    solve_xu << x_solve, u_solve;
    const double cost = evaluate(*ocp.lagrange_cost, xu) + evaluate(*ocp.mayer_cost, x);
    const double solve_cost =
        evaluate(*solve_ocp.lagrange_cost, solve_xu) + evaluate(*solve_ocp.mayer_cost, x_solve);
    EXPECT_NEAR(solve_cost, cost / (length * length), 1e-12 * cost / (length * length));
    EXPECT_LT((solve_ocp.control_upper - ocp.control_upper.cwiseQuotient(units.control))
                  .cwiseAbs()
                  .maxCoeff(),
              1e-12 * solve_ocp.control_upper.cwiseAbs().maxCoeff());
    if (robot) {
      const int nq = task.scene.numJoints();
      EXPECT_LT((solve_ocp.state_upper.head(nq) -
                 ocp.state_upper.head(nq).cwiseQuotient(units.state.head(nq)))
                    .cwiseAbs()
                    .maxCoeff(),
                1e-12 * solve_ocp.state_upper.head(nq).cwiseAbs().maxCoeff());
    }
  }
}

}  // namespace
