// Planning bodies of several spheres as their bounding discs (bounding_discs.cpp): the disc task,
// its pairs, and the disc guess mapped back (positions, the start yaw kept, each disc pair's
// multiplier on its nearest sphere pair); planPushes of a bar of spheres through them.
#include <gtest/gtest.h>

#include "fesd_trajopt/planning/bounding_discs.h"
#include "fesd_trajopt/planning/push_plan.h"

namespace {

/// A pusher at (-2, 0.4) and a turning bar of two spheres (radius 0.25 at y = +-0.4), yaw 0.
fesd::SceneTask barTask() {
  fesd::SceneTask task;
  fesd::SceneBody bar{"bar", 0.25, Eigen::Vector2d(0.0, 0.0)};
  bar.spheres = {{"bar/sphere_0", Eigen::Vector3d(0.0, -0.4, 0.0), 0.25},
                 {"bar/sphere_1", Eigen::Vector3d(0.0, 0.4, 0.0), 0.25}};
  fesd::turnAboutPressureCentre(bar);
  task.scene.bodies() = {{"pusher", 0.2, Eigen::Vector2d(-2.0, 0.4), true}, bar};
  task.bodies.resize(2);
  task.bodies[1].target = Eigen::Vector2d(1.0, 0.0);
  task.bodies[1].target_weight = 100.0;
  task.bodies[1].target_yaw = 0.3;
  task.bodies[1].target_yaw_weight = 10.0;
  task.horizon = 4.0;
  task.num_intervals = 8;
  return task;
}

TEST(BoundingDiscs, EachBodyIsOneDiscThatHoldsItsSpheres) {
  const fesd::SceneTask task = barTask();
  EXPECT_TRUE(fesd::hasCompositeBodies(task.scene));
  const fesd::SceneTask discs = fesd::boundingDiscTask(task);
  EXPECT_FALSE(fesd::hasCompositeBodies(discs.scene));
  EXPECT_DOUBLE_EQ(discs.scene.bodies()[1].radius, 0.65);
  EXPECT_FALSE(discs.scene.bodies()[1].turns);
  EXPECT_EQ(discs.scene.stateSize(), 4);
  EXPECT_FALSE(discs.bodies[1].hasYawTarget());
  EXPECT_TRUE(discs.bodies[1].hasTarget());
  // pusher/bar/sphere_0 and pusher/bar/sphere_1 (collision bodies 0 and 1, 2) are both the
  // discs' pusher/bar (0 and 1).
  const fesd::BoundingDiscPairs disc_pairs =
      fesd::boundingDiscPairs(task.scene, task.scene.allPairs());
  ASSERT_EQ(disc_pairs.pairs.size(), 1u);
  EXPECT_EQ(disc_pairs.pairs[0], (fesd::ContactPair{0, fesd::ContactPair::Kind::kBody, 1}));
  EXPECT_EQ(disc_pairs.disc_of, (std::vector<int>{0, 0}));
}

TEST(BoundingDiscs, TheDiscGuessPutsEachForceOnTheNearestSpherePair) {
  const fesd::SceneTask task = barTask();
  const std::vector<fesd::ContactPair> pairs = task.scene.allPairs();
  ASSERT_EQ(pairs.size(), 2u);  // the pusher with each sphere
  // The discs' guess: the pusher at (-0.85, 0.4), touching the bar's disc, pressing with 3.
  fesd::TrajectoryGuess disc_guess;
  disc_guess.state = [](double) { return Eigen::Vector4d(-0.85, 0.4, 0.0, 0.0).eval(); };
  disc_guess.multipliers = [](double) { return Eigen::VectorXd::Constant(1, 3.0); };
  const fesd::TrajectoryGuess guess =
      fesd::guessOfSpheres(task, pairs, fesd::boundingDiscPairs(task.scene, pairs), disc_guess);
  const Eigen::VectorXd x = guess.state(1.0);
  ASSERT_EQ(x.size(), 5);
  EXPECT_EQ(x.head(4), Eigen::Vector4d(-0.85, 0.4, 0.0, 0.0));
  EXPECT_EQ(x(4), task.scene.initialState()(4));  // the start yaw
  const Eigen::VectorXd lambda = guess.multipliers(1.0);
  EXPECT_EQ(lambda, Eigen::Vector2d(0.0, 3.0));  // sphere_1, at the pusher's height
}

TEST(BoundingDiscs, PushesOfABarOfSpheresArePlannedOnItsDisc) {
  const fesd::SceneTask task = barTask();
  const std::vector<fesd::ContactPair> pairs = task.scene.allPairs();
  const fesd::PushPlan plan = fesd::planPushes(task, pairs);
  const Eigen::VectorXd end = plan.guess.state(task.horizon);
  ASSERT_EQ(end.size(), task.scene.stateSize());
  EXPECT_LT((task.scene.position(1, end) - task.bodies[1].target).norm(), 1e-9);
  EXPECT_GT(plan.guess.multipliers(0.5 * (plan.contact_time + plan.release_time)).maxCoeff(), 0.0);
}

}  // namespace
