// The first pairs of a lazy solve (scene/lazy_pairs.cpp): those a guess presses on or brings
// within the margin of contact, and no others.
// For robots: the pairs the first guess calls for.
#include <memory>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/planning/robot_guess.h"
#include "fesd_trajopt/scene/lazy_pairs.h"
#include "support/robot_files.h"

namespace {

/// A pusher (R = 0.5) moving from (-3, 0) to (3, 0) in T = 2 past a puck at (0, 1.2) (gap 0.2
/// at the closest point), a far rock at (0, 5) and a post (R = 0.5) at (0, -1.15) (gap 0.15).
fesd::SceneTask passingTask() {
  fesd::SceneTask task;
  task.scene.bodies() = {{"pusher", 0.5, Eigen::Vector2d(-3.0, 0.0), true},
                         {"puck", 0.5, Eigen::Vector2d(0.0, 1.2), false},
                         {"rock", 0.5, Eigen::Vector2d(0.0, 5.0), false}};
  task.scene.obstacles() = {{"post", 0.5, Eigen::Vector2d(0.0, -1.15)}};
  task.bodies.resize(3);
  task.horizon = 2.0;
  task.num_intervals = 4;
  return task;
}

fesd::TrajectoryGuess straightPass(const fesd::SceneTask& task, int pressed_pair) {
  fesd::TrajectoryGuess guess;
  guess.state = [task](double t) {
    Eigen::VectorXd x = task.scene.initialState();
    x(0) = -3.0 + 3.0 * t;
    return x;
  };
  guess.multipliers = [pressed_pair](double t) {
    Eigen::VectorXd lambda = Eigen::VectorXd::Zero(4);
    if (t > 0.9 && t < 1.1) lambda(pressed_pair) = 0.5;
    return lambda;
  };
  return guess;
}

TEST(LazyPairs, TheGuessNeedsWhatItPressesOnAndWhatComesWithinTheMargin) {
  const fesd::SceneTask task = passingTask();
  const std::vector<fesd::ContactPair> candidates{{0, fesd::ContactPair::Kind::kBody, 1},
                                                  {0, fesd::ContactPair::Kind::kBody, 2},
                                                  {1, fesd::ContactPair::Kind::kBody, 2},
                                                  {0, fesd::ContactPair::Kind::kObstacle, 0}};
  // The puck's gap 0.2 is within a margin of 0.3 (R_i + R_j) but not of 0.1; the guess presses
  // on the post; the rock never comes close.
  fesd::PairSelection wide = fesd::pairsTheGuessNeeds(task.scene, task.horizon, candidates,
                                                      straightPass(task, 3), 0.3, 64);
  EXPECT_EQ(wide.modelled, (std::vector<bool>{true, false, false, true}));
  EXPECT_NE(wide.reasons[0].find("within the margin"), std::string::npos) << wide.reasons[0];
  EXPECT_NE(wide.reasons[3].find("in contact"), std::string::npos) << wide.reasons[3];
  fesd::PairSelection narrow = fesd::pairsTheGuessNeeds(task.scene, task.horizon, candidates,
                                                        straightPass(task, 3), 0.1, 64);
  EXPECT_EQ(narrow.modelled, (std::vector<bool>{false, false, false, true}));
  // A pair the guess presses on is needed whatever its gap: the far rock here.
  fesd::PairSelection pressed = fesd::pairsTheGuessNeeds(task.scene, task.horizon, candidates,
                                                         straightPass(task, 1), 0.1, 64);
  EXPECT_EQ(pressed.modelled, (std::vector<bool>{false, true, false, false}));
}
}  // namespace

namespace {

using fesd::ContactPair;

fesd::SceneTask armPush() {
  return fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
}

TEST(RobotLazyPairs, TheGuessCallsForThePushingSphereNotForTheFarOnes) {
  const fesd::SceneTask task = armPush();
  std::vector<ContactPair> candidates;
  for (const auto& d : fesd::decidePairs(task)) {
    if (d.modelled) candidates.push_back(d.pair);
  }
  const fesd::RobotGuess guess = fesd::planRobotGuess(task, candidates, 2);
  const std::vector<bool> needed =
      fesd::pairsTheGuessNeeds(task.scene, task.horizon, candidates, guess.guess, 0.1, 160)
          .modelled;
  for (size_t k = 0; k < candidates.size(); ++k) {
    const std::string name = task.scene.pairName(candidates[k]);
    if (name == "disc/hand/sphere_0") {
      EXPECT_TRUE(needed[k]);
    }
    if (name == "disc/upper_arm/sphere_0") {  // 0.1 from the shoulder: never near the disc
      EXPECT_FALSE(needed[k]);
    }
  }
}

}  // namespace
