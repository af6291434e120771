// Lazy pairs for robots (scene/robot_lazy_pairs.cpp): pair sizes, gaps along a path, the pairs
// the first guess calls for, and a solution's multipliers carried over to a larger pair set.
#include <memory>

#include <gtest/gtest.h>

#include "fesd_trajopt/scene/robot_guess.h"
#include "fesd_trajopt/scene/robot_lazy_pairs.h"
#include "fesd_trajopt/scene/robot_scenes.h"
#include "support/robot_files.h"

namespace {

using fesd::RobotPair;

fesd::RobotTask armPush() {
  return fesd::planarArmPushTask(
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot("planar_arm.urdf")));
}

RobotPair named(const fesd::RobotTask& task, const std::string& name) {
  for (const RobotPair& pair : task.scene.allPairs()) {
    if (task.scene.pairName(pair) == name) return pair;
  }
  ADD_FAILURE() << "no pair " << name;
  return {};
}

TEST(RobotLazyPairs, SizesAndGapsAlongAPath) {
  const fesd::RobotTask task = armPush();
  const RobotPair hand = named(task, "disc/hand/sphere_0");
  EXPECT_DOUBLE_EQ(fesd::robotPairSize(task.scene, hand), 0.05 + 0.035);
  // At q = 0 the arm lies along x with hand/sphere_0 at (0.75, 0), 0.15 from the disc's centre
  // at (0.6, 0); at q0 it is farther.
  Eigen::VectorXd along_x = task.scene.initialState();
  along_x.head(3).setZero();
  const std::vector<double> gaps =
      fesd::smallestPathGaps(task.scene, {hand}, {task.scene.initialState(), along_x});
  EXPECT_NEAR(gaps[0], 0.15 - 0.085, 1e-12);
}

TEST(RobotLazyPairs, TheGuessCallsForThePushingSphereNotForTheFarOnes) {
  const fesd::RobotTask task = armPush();
  std::vector<RobotPair> candidates;
  for (const auto& d : fesd::decideRobotPairs(task)) {
    if (d.modelled) candidates.push_back(d.pair);
  }
  const fesd::RobotGuess guess = fesd::planRobotGuess(task, candidates, 2);
  const std::vector<bool> needed =
      fesd::robotPairsTheGuessNeeds(task, candidates, guess.guess, 0.1, 160);
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

TEST(RobotLazyPairs, MultipliersFollowTheirPairs) {
  const fesd::RobotTask task = armPush();
  const RobotPair a = named(task, "disc/hand/sphere_0"), b = named(task, "disc/hand/sphere_1"),
                  c = named(task, "disc/forearm/sphere_2");
  fesd::Trajectory trajectory;
  fesd::ElementValues element;
  element.stage_states = Eigen::MatrixXd::Zero(5, 2);
  element.stage_multipliers = (Eigen::MatrixXd(2, 2) << 1, 2, 3, 4).finished();
  element.stage_constraints = Eigen::MatrixXd::Ones(2, 2);
  trajectory.elements.push_back(element);
  const fesd::Trajectory moved = fesd::trajectoryForPairs(trajectory, {a, b}, {c, b, a});
  EXPECT_EQ(moved.elements[0].stage_multipliers,
            (Eigen::MatrixXd(3, 2) << 0, 0, 3, 4, 1, 2).finished());
  EXPECT_EQ(moved.elements[0].stage_constraints, Eigen::MatrixXd::Zero(3, 2));
}

}  // namespace
