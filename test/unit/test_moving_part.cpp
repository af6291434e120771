// The moving part of a task (scene/moving_part.cpp): a passive body out of reach is left out of
// the model and keeps its place in the full-scene trajectory of a simulated push; guesses and
// trajectories of the full task map onto a part with other pairs; with a robot, the joints
// always move and its pairs' multipliers follow their pairs.
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/scene/moving_part.h"
#include "fesd_trajopt/scene/scene_task.h"
#include "support/robot_files.h"
#include "support/scene_tasks.h"

namespace {

/// The pushing task with a post (fesd_test::pushingTaskWithPost).
fesd::SceneTask pushingTask() {
  return fesd_test::pushingTaskWithPost();
}

TEST(MovingPart, APassiveBodyOutOfReachIsLeftOutAndKeepsItsPlace) {
  const fesd::SceneTask task = pushingTask();
  const std::vector<fesd::PairDecision> decisions = fesd::decidePairs(task);
  const fesd::MovingPart part = fesd::movingPart(task, decisions);
  EXPECT_EQ(part.bodies, (std::vector<int>{0, 1}));
  EXPECT_EQ(part.task.scene.stateSize(), 4);
  ASSERT_EQ(part.modelled.size(), 3u);
  for (const fesd::ContactPair& pair : part.modelled) EXPECT_LT(pair.body, 2);

  // Under u = (2, 0) the pusher touches the puck at t = 1; in contact the projection shares the
  // velocity: both move at 1 m/s, so p_pusher(2) = (0, 0) and p_puck(2) = (1, 0).
  fesd::SimulationOptions options;
  options.discretization.num_elements = 2;
  fesd::FesdIntegrator integrator(part.task.scene.model(part.modelled), options);
  const fesd::SimulationResult result = integrator.simulate(
      part.task.scene.initialState(), task.horizon, task.num_intervals, {Eigen::Vector2d(2, 0)});
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  const fesd::Trajectory full = fesd::fullSceneTrajectory(task, part, result.trajectory);
  Eigen::VectorXd expected(6);
  expected << 0.0, 0.0, 1.0, 0.0, 100.0, 100.0;
  EXPECT_LT((full.finalState() - expected).norm(), 1e-9);
  for (const fesd::ElementValues& element : full.elements) {
    ASSERT_EQ(element.stage_states.rows(), 6);
    EXPECT_TRUE(
        (element.stage_states.bottomRows(2).colwise() - Eigen::Vector2d(100, 100)).isZero(0.0));
  }
  ASSERT_FALSE(full.switches.empty());
  EXPECT_NEAR(full.switches.front().time, 1.0, 1e-9);
  EXPECT_EQ(part.task.scene.pairName(part.modelled[full.switches.front().constraint]),
            task.scene.pairName(decisions[0].pair));
}

// A turning box out of reach (boxIntoACorner's, moved far away) is left out with its three
// coordinates; a turning box in reach keeps them in the part: states map both ways unchanged.
TEST(MovingPart, TurningBodiesKeepTheirTurnInOrOutOfThePart) {
  fesd::SceneTask task = fesd_test::boxIntoACorner();
  task.scene.bodies().push_back(task.scene.bodies()[1]);
  task.scene.bodies().back().name = "far_box";
  for (fesd::FreeBodySphere& sphere : task.scene.bodies().back().spheres) {
    sphere.name = "far_box" + sphere.name.substr(3);
  }
  task.scene.bodies().back().position = Eigen::Vector2d(100.0, 100.0);
  task.bodies.push_back(fesd::BodyTask{});
  const fesd::MovingPart part = fesd::movingPart(task, fesd::decidePairs(task));
  EXPECT_EQ(part.bodies, (std::vector<int>{0, 1}));
  EXPECT_EQ(part.task.scene.stateSize(), 5);
  Eigen::VectorXd x = task.scene.initialState();
  ASSERT_EQ(x.size(), 8);
  x.head(5) << 0.1, 0.2, 0.3, 0.4, 0.5;
  const Eigen::VectorXd moving = fesd::partState(task, part, x);
  EXPECT_EQ(moving, x.head(5));
  fesd::Trajectory trajectory;
  trajectory.states = {moving};
  const fesd::Trajectory full = fesd::fullSceneTrajectory(task, part, trajectory);
  EXPECT_EQ(full.states[0], x);  // the far box at its start, its yaw too
}

TEST(MovingPart, GuessesAndTrajectoriesMapOntoAPartWithOtherPairs) {
  const fesd::SceneTask task = pushingTask();  // pusher, puck, rock (far); post
  const fesd::ContactPair pusher_puck{0, fesd::ContactPair::Kind::kBody, 1},
      puck_post{1, fesd::ContactPair::Kind::kObstacle, 0},
      pusher_rock{0, fesd::ContactPair::Kind::kBody, 2};
  std::vector<fesd::PairDecision> decisions;
  for (const fesd::ContactPair& pair : task.scene.allPairs()) {
    decisions.push_back({pair, pair == pusher_rock || pair == puck_post, ""});
  }
  const fesd::MovingPart part = fesd::movingPart(task, decisions);
  ASSERT_EQ(part.bodies, (std::vector<int>{0, 1, 2}));
  ASSERT_EQ(part.modelled_in_task, (std::vector<fesd::ContactPair>{pusher_rock, puck_post}));

  // A guess whose multipliers belong to (pusher/puck, puck/post): the part takes the post's.
  fesd::TrajectoryGuess guess;
  guess.state = [&](double t) { return Eigen::VectorXd(task.scene.initialState() * (1.0 + t)); };
  guess.multipliers = [](double t) { return Eigen::Vector2d(1.0 + t, 2.0 + t); };
  const fesd::TrajectoryGuess mapped = fesd::partGuess(task, part, guess, {pusher_puck, puck_post});
  EXPECT_EQ(mapped.state(0.5), guess.state(0.5));
  EXPECT_EQ(mapped.multipliers(0.5), Eigen::Vector2d(0.0, 2.5));

  // A trajectory of a part without the rock: the rock keeps its state, multipliers re-ordered.
  for (fesd::PairDecision& d : decisions) d.modelled = d.pair == pusher_puck;
  const fesd::MovingPart small = fesd::movingPart(task, decisions);
  ASSERT_EQ(small.bodies, (std::vector<int>{0, 1}));
  fesd::Trajectory trajectory;
  trajectory.states = {Eigen::Vector4d(-3, 0, 0, 0), Eigen::Vector4d(-1, 0, 0, 0)};
  trajectory.elements.push_back({0, 0.0, 1.0, Eigen::Vector4d(-1, 0, 0, 0),
                                 Eigen::MatrixXd::Constant(1, 1, 0.7), Eigen::MatrixXd::Zero(1, 1),
                                 Eigen::VectorXd()});
  const fesd::Trajectory full = fesd::fullSceneTrajectory(task, small, trajectory);
  const fesd::Trajectory grown = fesd::partTrajectory(task, part, full, small.modelled_in_task);
  Eigen::VectorXd expected(6);
  expected << -1, 0, 0, 0, 100, 100;
  EXPECT_EQ(grown.states[1], expected);
  EXPECT_EQ(grown.elements[0].stage_states.col(0), expected);
  EXPECT_EQ(grown.elements[0].stage_multipliers, Eigen::Vector2d::Zero());  // neither modelled
  const fesd::Trajectory same = fesd::partTrajectory(task, small, full, small.modelled_in_task);
  EXPECT_EQ(same.elements[0].stage_multipliers(0, 0), 0.7);
}

TEST(MovingPart, ARobotsJointsMoveAndItsPairsMultipliersFollowTheirPairs) {
  const fesd::SceneTask task = fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
  const auto named = [&](const std::string& name) {
    for (const fesd::ContactPair& pair : task.scene.allPairs()) {
      if (task.scene.pairName(pair) == name) return pair;
    }
    ADD_FAILURE() << "no pair " << name;
    return fesd::ContactPair{};
  };
  const fesd::ContactPair a = named("disc/hand/sphere_0"), b = named("disc/hand/sphere_1"),
                          c = named("disc/forearm/sphere_2");
  const fesd::MovingPart part =
      fesd::movingPart(task, {{c, true, ""}, {b, true, ""}, {a, true, ""}});
  EXPECT_EQ(part.bodies, (std::vector<int>{0}));
  EXPECT_EQ(part.task.scene.stateSize(), 5);  // three joints, the disc
  EXPECT_EQ(part.modelled, (std::vector<fesd::ContactPair>{c, b, a}));
  fesd::Trajectory trajectory;
  fesd::ElementValues element;
  element.stage_states = Eigen::MatrixXd::Zero(5, 2);
  element.stage_multipliers = (Eigen::MatrixXd(2, 2) << 1, 2, 3, 4).finished();
  element.stage_constraints = Eigen::MatrixXd::Ones(2, 2);
  trajectory.elements.push_back(element);
  const fesd::Trajectory moved = fesd::partTrajectory(task, part, trajectory, {a, b});
  EXPECT_EQ(moved.elements[0].stage_multipliers,
            (Eigen::MatrixXd(3, 2) << 0, 0, 3, 4, 1, 2).finished());
  EXPECT_EQ(moved.elements[0].stage_constraints, Eigen::MatrixXd::Zero(3, 2));
}

}  // namespace
