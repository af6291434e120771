// The turning push planner (planning/turning_push.cpp): contacts behind a body's spheres with
// their levers, and Push-T plans that end at the pose, touch without cutting in, and whose
// forces move the T as the model's projection does.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/push_t.h"
#include "fesd_trajopt/model/dcs_model.h"
#include "fesd_trajopt/planning/turning_push.h"

namespace {

fesd::SceneBody threeSphereBar() {
  fesd::SceneBody bar{"bar", 0.75, Eigen::Vector2d::Zero(), false};
  for (double x : {-0.5, 0.0, 0.5}) {
    bar.spheres.push_back({"bar/sphere", Eigen::Vector3d(x, 0.0, 0.0), 0.25});
  }
  return bar;
}

TEST(PushContacts, BehindEverySphereThePusherReachesWithItsLever) {
  const fesd::SceneBody bar = threeSphereBar();
  // From below, along +y: every sphere, the pusher 0.45 below its centre; lever x (o x n).
  const std::vector<fesd::PushContact> side =
      fesd::pushContacts(bar, 0.2, Eigen::Vector2d::UnitY());
  ASSERT_EQ(side.size(), 3u);
  for (int k = 0; k < 3; ++k) {
    EXPECT_EQ(side[k].sphere, k);
    EXPECT_NEAR((side[k].pusher - Eigen::Vector2d(-0.5 + 0.5 * k, -0.45)).norm(), 0.0, 1e-15);
    EXPECT_NEAR(side[k].lever, -0.5 + 0.5 * k, 1e-15);
  }
  // Along the bar, +x: only the left end is reached; the others lie behind it.
  const std::vector<fesd::PushContact> end = fesd::pushContacts(bar, 0.2, Eigen::Vector2d::UnitX());
  ASSERT_EQ(end.size(), 1u);
  EXPECT_EQ(end[0].sphere, 0);
  EXPECT_NEAR(end[0].lever, 0.0, 1e-15);
}

/// The smallest gap between the pusher (body 0) and the T's spheres (body 1) at x.
double smallestGap(const fesd::Scene& scene, const Eigen::VectorXd& x) {
  const fesd::SceneBody& t = scene.bodies()[1];
  const Eigen::Vector2d pusher = scene.position(0, x);
  const Eigen::Rotation2Dd turn(scene.yaw(1, x));
  double gap = std::numeric_limits<double>::infinity();
  for (const fesd::FreeBodySphere& sphere : t.spheres) {
    const Eigen::Vector2d centre = scene.position(1, x) + turn * sphere.offset.head<2>();
    gap = std::min(gap, (pusher - centre).norm() - sphere.radius - scene.bodies()[0].radius);
  }
  return gap;
}

TEST(TurningPush, PushTPlansEndAtThePoseTouchingTheTWithoutCuttingIn) {
  for (unsigned seed = 0; seed < 16; ++seed) {
    const fesd::SceneTask task = fesd::push_t::randomStart(seed);
    const fesd::Scene& scene = task.scene;
    const std::vector<fesd::ContactPair> pairs = scene.allPairs();
    const std::optional<fesd::PushPlan> plan = fesd::planTurningPush(task, pairs);
    ASSERT_TRUE(plan) << seed;
    EXPECT_TRUE(plan->turns_bodies);
    ASSERT_EQ(plan->guess.controls.size(), static_cast<size_t>(task.num_intervals));
    EXPECT_LT((plan->guess.state(0.0) - scene.initialState()).norm(), 1e-15) << seed;
    const Eigen::VectorXd end = plan->guess.state(task.horizon);
    EXPECT_LT((scene.position(1, end) - task.bodies[1].target).norm(), 1e-12) << seed;
    EXPECT_NEAR(scene.yaw(1, end), task.bodies[1].target_yaw, 1e-12) << seed;
    // Never into the T; touching it whenever it moves.
    int moving = 0, touching = 0;
    for (int k = 0; k <= 2000; ++k) {
      const double t = task.horizon * k / 2000.0;
      const Eigen::VectorXd x = plan->guess.state(t);
      const double gap = smallestGap(scene, x);
      EXPECT_GE(gap, -1e-12) << seed << " at t = " << t;
      if (k > 0 && (x - plan->guess.state(t - 1e-6)).segment<3>(2).norm() > 0.0) {
        ++moving;
        touching += gap < 1e-12;
      }
    }
    // The T moves only when pushed; the pusher goes round it between pushes.
    EXPECT_EQ(touching, moving) << seed;
    EXPECT_GT(moving, 200) << seed;
  }
}

TEST(TurningPush, ItsForcesAndControlsMoveTheBodiesAsTheModelDoes) {
  // The model's velocity f + grad c lambda with the plan's lambda and controls: on the arcs the
  // T's rows (position and s = rho yaw) are the plan's own velocity; over every control interval
  // the pusher's mean is its planned displacement; no control beyond the speed bound. Seed 2
  // turns by -144 degrees; the second T starts square to the axes (contacts in the corner
  // between bar and stem touch two spheres there).
  for (const fesd::SceneTask& task :
       {fesd::push_t::randomStart(2),
        fesd::push_t::task(Eigen::Vector2d(-2.0, 0.5), 0.0, Eigen::Vector2d(-2.0, -2.5))}) {
    const fesd::Scene& scene = task.scene;
    const std::vector<fesd::ContactPair> pairs = scene.allPairs();
    const std::optional<fesd::PushPlan> plan = fesd::planTurningPush(task, pairs);
    ASSERT_TRUE(plan);
    const std::shared_ptr<const fesd::DcsModel> model = scene.model(pairs);
    const int n = scene.stateSize(), m = scene.controlSize(), p = static_cast<int>(pairs.size());
    const auto modelVelocity = [&](double t, const Eigen::VectorXd& u) {
      Eigen::VectorXd z(n + m + p), velocity(n);
      z << plan->guess.state(t), u, plan->guess.multipliers(t);
      model->velocity()->evaluate(z.data(), velocity.data());
      return velocity;
    };
    int on_arcs = 0;
    for (int k = 1; k < 400; ++k) {
      const double t = task.horizon * (k + 0.5) / 400.0, dt = 1e-6;
      const Eigen::VectorXd planned =
          (plan->guess.state(t + dt) - plan->guess.state(t - dt)) / (2 * dt);
      // On the arcs (the straight pushes' lever would turn the T a little: the NLP's to mend).
      if (plan->guess.multipliers(t).maxCoeff() <= 0.0 || std::fabs(planned(4)) < 1e-3) continue;
      const Eigen::VectorXd velocity = modelVelocity(t, Eigen::VectorXd::Zero(m));
      EXPECT_LT((velocity.segment<3>(2) - planned.segment<3>(2)).norm(),
                1e-5 * planned.segment<3>(2).norm())
          << "t = " << t;
      ++on_arcs;
    }
    EXPECT_GT(on_arcs, 20);
    const double interval = task.horizon / task.num_intervals;
    for (int j = 0; j < task.num_intervals; ++j) {
      const Eigen::VectorXd& u = plan->guess.controls[j];
      EXPECT_LE(u.cwiseAbs().maxCoeff(), task.bodies[0].max_speed) << "interval " << j;
      Eigen::Vector2d moved = Eigen::Vector2d::Zero();
      constexpr int kSamples = 64;
      for (int i = 0; i < kSamples; ++i) {
        moved +=
            modelVelocity((j + (i + 0.5) / kSamples) * interval, u).head<2>() * interval / kSamples;
      }
      const Eigen::Vector2d planned =
          (plan->guess.state((j + 1) * interval) - plan->guess.state(j * interval)).head<2>();
      EXPECT_LT((moved - planned).norm(), 0.02 * task.bodies[0].max_speed * interval)
          << "interval " << j;
    }
  }
}

TEST(TurningPush, OnlyOnePusherAndOneTurningBodyInAnOpenPlane) {
  const fesd::SceneTask task = fesd::push_t::randomStart(0);
  fesd::SceneTask walled = task;
  walled.scene.walls().push_back({"floor", Eigen::Vector2d::UnitY(), -10.0});
  EXPECT_FALSE(fesd::planTurningPush(walled, walled.scene.allPairs()));
  fesd::SceneTask untargeted = task;
  untargeted.bodies[1].target_yaw_weight = 0.0;
  EXPECT_FALSE(fesd::planTurningPush(untargeted, untargeted.scene.allPairs()));
  fesd::SceneTask half_turn = task;
  half_turn.bodies[1].target_yaw = task.scene.bodies()[1].yaw + 3.1;
  EXPECT_FALSE(fesd::planTurningPush(half_turn, half_turn.scene.allPairs()));
  // Without the pusher's pairs with the T the guess has no forces to give.
  EXPECT_FALSE(fesd::planTurningPush(task, {}));
  fesd::SceneTask slow = task;
  slow.bodies[0].max_speed = 0.01;
  EXPECT_FALSE(fesd::planTurningPush(slow, slow.scene.allPairs()));
}

}  // namespace
