// The scene model (scene/scene.cpp). Free bodies: the contact model's velocity and constraint
// derivatives against central finite differences in 2-D and 3-D, and the constraint values pair
// by pair. Robots in scenes: the state's layout, which pairs exist (spheres on one link never
// pair, self-collision only on request between non-adjacent links, SRDF pairs left out, a sphere
// fixed to the world only against free bodies), pair names and gaps, and the analytic check: the
// shoulder turning at constant speed meets a post when and where geometry says, to 1e-8.
#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/kinematics/srdf.h"
#include "fesd_trajopt/scene/scene.h"
#include "support/finite_differences.h"
#include "support/robot_files.h"
#include "support/scene_tasks.h"

namespace {

using fesd_test::checkAgainstFiniteDifferences;
using fesd_test::kTolerance;
using fesd_test::randomVector;

/// A scene with every kind of contact pair: bodies (actuated and passive), an obstacle, walls.
fesd::Scene mixedScene(int dimension, std::mt19937& random) {
  fesd::Scene scene(dimension);
  for (int b = 0; b < 4; ++b) {
    scene.bodies().push_back({"body" + std::to_string(b), 0.5 + 0.2 * b,
                              randomVector(dimension, random, -3.0, 3.0), b % 2 == 0});
  }
  scene.obstacles().push_back({"post", 0.7, randomVector(dimension, random, -3.0, 3.0)});
  Eigen::VectorXd normal = randomVector(dimension, random);
  scene.walls().push_back({"slanted", normal.normalized(), -4.0});
  Eigen::VectorXd axis = Eigen::VectorXd::Zero(dimension);
  axis(1) = 1.0;
  scene.walls().push_back({"floor", axis, -5.0});  // a normal with zero components
  return scene;
}

class SceneDerivatives : public ::testing::TestWithParam<int> {};

TEST_P(SceneDerivatives, VelocityAndConstraintsAgainstFiniteDifferences) {
  std::mt19937 random(23);
  const fesd::Scene scene = mixedScene(GetParam(), random);
  const auto pairs = scene.allPairs();
  const auto model = scene.model(pairs);
  EXPECT_EQ(model->constraintSize(), 6 + 4 + 8);  // 6 body pairs, 4 obstacle, 8 wall pairs
  EXPECT_EQ(model->controlSize(), 2 * GetParam());
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd z = randomVector(model->velocity()->inputSize(), random, -3.0, 3.0);
    const auto velocity = checkAgainstFiniteDifferences(*model->velocity(), z,
                                                        randomVector(scene.stateSize(), random));
    EXPECT_LT(velocity.jacobian, kTolerance);
    EXPECT_LT(velocity.hessian, kTolerance);
    const Eigen::VectorXd x = z.head(scene.stateSize());
    const auto constraints = checkAgainstFiniteDifferences(
        *model->constraints(), x, randomVector(model->constraintSize(), random));
    EXPECT_LT(constraints.jacobian, kTolerance);
    EXPECT_LT(constraints.hessian, kTolerance);
    // The constraint values are the geometric ones, pair by pair.
    Eigen::VectorXd c(model->constraintSize());
    model->constraints()->evaluate(x.data(), c.data());
    for (size_t k = 0; k < pairs.size(); ++k) {
      EXPECT_DOUBLE_EQ(c(k), scene.constraintValue(pairs[k], x)) << scene.pairName(pairs[k]);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(PlanarAndSpatial, SceneDerivatives, ::testing::Values(2, 3));

}  // namespace

namespace {

using fesd::ContactPair;
using fesd::Scene;

std::shared_ptr<const fesd::KinematicModel> shipped(const std::string& name) {
  return std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot(name));
}

/// The planar arm at q = 0 with a passive disc, a post and a wall.
Scene armScene() {
  fesd::Scene discs(2);
  discs.bodies().push_back({"disc", 0.05, Eigen::Vector2d(0.6, 0.3), false});
  discs.obstacles().push_back({"post", 0.05, Eigen::Vector2d(-0.5, 0.5)});
  discs.walls().push_back({"floor", Eigen::Vector2d(0.0, 1.0), -1.0});
  return robotInScene(shipped("planar_arm.urdf"), Eigen::Vector3d::Zero(), discs);
}

std::vector<std::string> pairNames(const Scene& scene) {
  std::vector<std::string> names;
  for (const ContactPair& pair : scene.allPairs()) names.push_back(scene.pairName(pair));
  return names;
}

bool contains(const std::vector<std::string>& names, const std::string& name) {
  return std::find(names.begin(), names.end(), name) != names.end();
}

TEST(Scene, StateIsJointsThenBodies) {
  const Scene scene = armScene();
  EXPECT_EQ(scene.stateSize(), 3 + 2);
  EXPECT_EQ(scene.controlSize(), 3);
  EXPECT_EQ(scene.stateIndex(0), 3);
  EXPECT_EQ(scene.initialState(), (Eigen::VectorXd(5) << 0, 0, 0, 0.6, 0.3).finished());
  ASSERT_EQ(scene.collisionBodies().size(), 1u + 9u);
  EXPECT_EQ(scene.collisionBodies()[0].name, "disc");
  EXPECT_EQ(scene.collisionBodies()[scene.sphereBody(8)].name, "hand/sphere_1");
}

TEST(Scene, PairsOfEveryKindButNoSelfCollisionByDefault) {
  const Scene scene = armScene();
  const std::vector<std::string> names = pairNames(scene);
  EXPECT_TRUE(contains(names, "disc/hand/sphere_1"));
  EXPECT_TRUE(contains(names, "disc/base/sphere_0"));  // the base is an obstacle to the disc
  EXPECT_TRUE(contains(names, "hand/sphere_1/post"));
  EXPECT_TRUE(contains(names, "hand/sphere_1/floor"));
  EXPECT_FALSE(contains(names, "base/sphere_0/post"));  // fixed to the world: never moves
  EXPECT_FALSE(contains(names, "upper_arm/sphere_0/hand/sphere_1"));
  // 9 spheres and the disc; 8 moving spheres with the post and the floor; the disc's own two.
  EXPECT_EQ(names.size(), 9u + 8u * 2u + 2u);
}

TEST(Scene, SelfCollisionOnlyBetweenNonAdjacentLinksNotDisabled) {
  Scene scene = armScene();
  scene.self_collision = true;
  std::vector<std::string> names = pairNames(scene);
  EXPECT_TRUE(contains(names, "upper_arm/sphere_0/hand/sphere_1"));
  EXPECT_FALSE(contains(names, "upper_arm/sphere_0/upper_arm/sphere_1"));  // same link
  EXPECT_FALSE(contains(names, "upper_arm/sphere_2/forearm/sphere_0"));    // adjacent
  EXPECT_FALSE(contains(names, "forearm/sphere_0/hand/sphere_0"));         // adjacent
  // The base (fixed to the world) and the forearm are not adjacent; 0.06 + 0.045 < 0.4 apart.
  EXPECT_TRUE(contains(names, "base/sphere_0/forearm/sphere_0"));
  // base/upper_arm adjacent: upper_arm's joint has no parent joint, the base none at all.
  EXPECT_FALSE(contains(names, "base/sphere_0/upper_arm/sphere_0"));
  scene.disabled_link_pairs.emplace_back("hand", "upper_arm");
  names = pairNames(scene);
  EXPECT_FALSE(contains(names, "upper_arm/sphere_0/hand/sphere_1"));
  EXPECT_TRUE(contains(names, "base/sphere_0/hand/sphere_1"));
}

TEST(Scene, GapsAreDistancesBetweenSurfaces) {
  const Scene scene = armScene();
  const Eigen::VectorXd x0 = scene.initialState();
  for (const ContactPair& pair : scene.allPairs()) {
    if (scene.pairName(pair) == "disc/hand/sphere_1") {
      EXPECT_NEAR(scene.pairGap(pair, x0), std::hypot(0.3, 0.3) - 0.08, 1e-12);
    }
    if (scene.pairName(pair) == "hand/sphere_1/floor") {
      EXPECT_NEAR(scene.pairGap(pair, x0), 1.0 - 0.03, 1e-12);
    }
  }
}

TEST(Scene, ANameNamesItsBodyOrTheSpheresOfItsLink) {
  EXPECT_TRUE(fesd::namesSide("hand", "hand"));
  EXPECT_TRUE(fesd::namesSide("hand", "hand/sphere_1"));
  EXPECT_TRUE(fesd::namesSide("hand/sphere_1", "hand/sphere_1"));
  EXPECT_FALSE(fesd::namesSide("hand/sphere_1", "hand/sphere_10"));
  EXPECT_FALSE(fesd::namesSide("han", "hand/sphere_1"));
  EXPECT_FALSE(fesd::namesSide("hand", "handle"));
}

TEST(Scene, AFreeBodyWithSeveralSpheresPairsSphereBySphere) {
  fesd::Scene discs(2);
  discs.bodies().push_back({"bar", 0.1, Eigen::Vector2d(0.6, 0.3), false});
  discs.bodies().push_back({"disc", 0.05, Eigen::Vector2d(0.6, 0.6), false});
  discs.walls().push_back({"floor", Eigen::Vector2d(0.0, 1.0), -1.0});
  const std::vector<fesd::FreeBodySphere> bar = {
      {"bar/sphere_0", Eigen::Vector3d(-0.06, 0.0, 0.0), 0.04},
      {"bar/sphere_1", Eigen::Vector3d(0.06, 0.0, 0.0), 0.04}};
  discs.bodies()[0].spheres = bar;
  const Scene scene = robotInScene(shipped("planar_arm.urdf"), Eigen::Vector3d::Zero(), discs);
  ASSERT_EQ(scene.collisionBodies().size(), 2u + 1u + 9u);
  EXPECT_EQ(scene.freeBodyCollisionBodies(0), (std::vector<int>{0, 1}));
  EXPECT_EQ(scene.freeBodyCollisionBodies(1), (std::vector<int>{2}));
  EXPECT_EQ(scene.collisionBodies()[scene.sphereBody(8)].name, "hand/sphere_1");
  const std::vector<std::string> names = pairNames(scene);
  EXPECT_FALSE(contains(names, "bar/sphere_0/bar/sphere_1"));  // one rigid body
  for (const char* name : {"bar/sphere_0/disc", "bar/sphere_1/disc", "bar/sphere_1/hand/sphere_1",
                           "bar/sphere_0/floor", "disc/hand/sphere_1"}) {
    EXPECT_TRUE(contains(names, name)) << name;
  }
  const std::vector<fesd::CollisionBody> bodies = scene.collisionBodies();
  for (int c = 0; c < static_cast<int>(bodies.size()); ++c) {
    EXPECT_EQ(scene.collisionRadius(c), bodies[c].radius) << bodies[c].name;
  }
  EXPECT_THROW(scene.collisionRadius(static_cast<int>(bodies.size())), std::out_of_range);
  EXPECT_THROW(scene.collisionRadius(-1), std::out_of_range);
  const Eigen::VectorXd x0 = scene.initialState();
  for (const ContactPair& pair : scene.allPairs()) {
    const std::string name = scene.pairName(pair);
    if (name == "bar/sphere_1/disc") {
      EXPECT_NEAR(scene.pairGap(pair, x0), std::hypot(0.06, 0.3) - 0.09, 1e-12);
    }
    if (name == "bar/sphere_0/floor") {
      EXPECT_NEAR(scene.pairGap(pair, x0), 1.3 - 0.04, 1e-12);
    }
    if (name == "bar/sphere_1/hand/sphere_1") {  // the hand's tip sphere at (0.9, 0), r 0.03
      EXPECT_NEAR(scene.pairGap(pair, x0), std::hypot(0.24, 0.3) - 0.07, 1e-12);
    }
  }
}

TEST(Scene, ShoulderTurningAtConstantSpeedMeetsThePostAtTheComputedTime) {
  // At q = 0 the arm lies along x with its tip sphere (radius 0.03) at 0.9. The shoulder turning
  // at omega sweeps it along the circle of radius 0.9; a post of radius 0.05 on that circle at
  // angle phi is met when the chord between them is 0.08: theta* = phi - 2 asin(0.08 / 1.8).
  const double omega = 0.5, phi = 0.6, radius = 0.9, radii = 0.03 + 0.05;
  fesd::Scene discs(2);
  discs.obstacles().push_back(
      {"post", 0.05, Eigen::Vector2d(radius * std::cos(phi), radius * std::sin(phi))});
  const Scene scene = robotInScene(shipped("planar_arm.urdf"), Eigen::Vector3d::Zero(), discs);
  std::vector<ContactPair> pairs;
  int tip_pair = -1;
  for (const ContactPair& pair : scene.allPairs()) {
    if (scene.pairName(pair) == "hand/sphere_1/post") tip_pair = static_cast<int>(pairs.size());
    pairs.push_back(pair);
  }
  ASSERT_GE(tip_pair, 0);
  fesd::SimulationOptions options;
  options.discretization.num_elements = 3;
  fesd::FesdIntegrator integrator(scene.model(pairs), options);
  const double horizon = 2.0;
  const fesd::SimulationResult result =
      integrator.simulate(scene.initialState(), horizon, 4, {Eigen::Vector3d(omega, 0.0, 0.0)});
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  const double contact_angle = phi - 2.0 * std::asin(radii / (2.0 * radius));
  const double expected_time = contact_angle / omega;
  int contacts = 0;
  for (const fesd::SwitchEvent& event : result.trajectory.switches) {
    if (event.kind != fesd::SwitchEvent::Kind::kContact) continue;
    ++contacts;
    EXPECT_EQ(event.constraint, tip_pair) << scene.pairName(pairs[event.constraint]);
    EXPECT_NEAR(event.time, expected_time, 1e-8);
    const Eigen::VectorXd& x = result.trajectory.states[event.element];
    EXPECT_NEAR(x(0), contact_angle, 1e-8);
    EXPECT_NEAR(scene.pairGap(pairs[tip_pair], x), 0.0, 1e-8);
  }
  EXPECT_EQ(contacts, 1);
  // Afterwards the arm stays out of the post at every element boundary.
  for (const Eigen::VectorXd& x : result.trajectory.states) {
    EXPECT_GT(scene.pairGap(pairs[tip_pair], x), -1e-8);
  }
}

}  // namespace

namespace {

TEST(Scene, SrdfDisabledPairsLeaveSelfCollisionOfThePanda) {
  fesd::Scene discs(3);
  const Eigen::VectorXd ready =
      (Eigen::VectorXd(7) << 0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785).finished();
  Scene scene = robotInScene(shipped("panda_spherized.urdf"), ready, discs);
  EXPECT_TRUE(pairNames(scene).empty());  // nothing else in the scene, no self-collision
  scene.self_collision = true;
  const size_t all_self = scene.allPairs().size();
  EXPECT_GT(all_self, 0u);
  const fesd::SrdfDisabledCollisions srdf =
      fesd::disabledCollisionsFromSrdf(fesd_test::readRobotFile("panda.srdf"));
  ASSERT_EQ(srdf.error, "");
  scene.disabled_link_pairs = srdf.pairs;
  const std::vector<ContactPair> kept = scene.allPairs();
  EXPECT_LT(kept.size(), all_self);
  const Eigen::VectorXd x0 = scene.initialState();
  for (const ContactPair& pair : kept) {
    const auto link = [&](int body) {
      return scene.robot()
          .links[scene.robot().spheres[scene.collisionBodies()[body].sphere].link]
          .name;
    };
    for (const auto& [a, b] : srdf.pairs) {
      EXPECT_FALSE((link(pair.body) == a && link(pair.other) == b) ||
                   (link(pair.body) == b && link(pair.other) == a))
          << scene.pairName(pair);
    }
    EXPECT_GE(scene.pairGap(pair, x0), 0.0) << scene.pairName(pair);
  }
}

// A turning body: (position, s = rho yaw) in the state after a translating one, its spheres
// turned by its yaw; turnAboutPressureCentre moves it to its spheres' centre of pressure.
TEST(SceneWithATurningBody, StateLayoutYawAndCentreOfPressure) {
  fesd::SceneBody bar{"bar", 0.1, Eigen::Vector2d(1.0, 2.0)};
  bar.spheres = {{"bar/sphere_0", Eigen::Vector3d(0.0, 0.0, 0.0), 0.1},
                 {"bar/sphere_1", Eigen::Vector3d(0.0, 0.6, 0.0), 0.2}};  // areas 1 : 4
  bar.yaw = M_PI / 2;
  EXPECT_EQ(fesd::boundingRadius(bar), 0.8);
  EXPECT_EQ(fesd::turningBodyProblem(bar), "");  // nothing to check while it does not turn
  bar.turns = true;
  EXPECT_NE(fesd::turningBodyProblem(bar).find("turning radius"), std::string::npos);
  fesd::turnAboutPressureCentre(bar);
  EXPECT_EQ(fesd::turningBodyProblem(bar), "");
  // The centre of pressure at 0.48 along the bar, turned by 90 degrees: 0.48 to the left.
  EXPECT_LT((bar.position - Eigen::Vector2d(1.0 - 0.48, 2.0)).norm(), 1e-12);
  EXPECT_LT((bar.spheres[1].offset - Eigen::Vector3d(0.0, 0.12, 0.0)).norm(), 1e-12);
  EXPECT_GT(bar.turning_radius, 0.0);

  Scene scene(2);
  scene.bodies() = {{"pusher", 0.2, Eigen::Vector2d(-1.0, 0.0), true}, bar};
  EXPECT_EQ(scene.coordinates(0), 2);
  EXPECT_EQ(scene.coordinates(1), 3);
  EXPECT_EQ(scene.stateIndex(1), 2);
  EXPECT_EQ(scene.stateSize(), 5);
  const Eigen::VectorXd x0 = scene.initialState();
  EXPECT_NEAR(x0(4), bar.turning_radius * M_PI / 2, 1e-15);
  EXPECT_NEAR(scene.yaw(1, x0), M_PI / 2, 1e-15);
  EXPECT_EQ(scene.yaw(0, x0), 0.0);
  // The far sphere at the position plus R(90 deg) (0, 0.12): (-0.12, 0).
  const fesd::CollisionCentre& far = scene.collisionBodies()[2].centre;
  fesd::CentreEvaluator evaluator(nullptr, 2);
  evaluator.setState(x0.data());
  EXPECT_LT((evaluator.position(far) - Eigen::Vector3d(0.52 - 0.12, 2.0, 0.0)).norm(), 1e-12);
  // setInitialState reads the yaw back.
  Eigen::VectorXd moved = x0;
  moved(4) = bar.turning_radius * 0.25;
  scene.setInitialState(moved);
  EXPECT_NEAR(scene.bodies()[1].yaw, 0.25, 1e-15);
  // Only passive bodies turn.
  scene.bodies()[1].actuated = true;
  EXPECT_THROW(scene.model(scene.allPairs()), std::invalid_argument);
}

}  // namespace

namespace {

/// fesd_test::puckOnATable's scene with a side wall that touches the puck too.
fesd::Scene tableScene() {
  fesd::Scene scene = fesd_test::puckOnATable().scene;
  scene.walls().push_back({"side", Eigen::Vector3d::UnitY(), -0.05});
  return scene;
}

// A body resting on a level wall (within 1 % of its radius) slides on it: its height is held,
// the contacts' normal force goes into the wall, and the two are no contact pair. A floating
// body, a tilted wall it touches, a planar scene and kNone leave every wall a pair.
TEST(SceneSupports, ABodyRestingOnALevelWallSlidesOnIt) {
  fesd::Scene scene = tableScene();
  EXPECT_TRUE(scene.isLevel(0));
  EXPECT_FALSE(scene.isLevel(1));
  EXPECT_EQ(scene.restingWalls(1), std::vector<int>{0});  // the side wall is not level
  EXPECT_EQ(scene.supportOf(1), 0);
  EXPECT_EQ(scene.supportOf(0), -1);  // 0.02 above the table: floating
  const std::vector<std::string> names = pairNames(scene);
  EXPECT_FALSE(contains(names, "puck/table"));
  EXPECT_TRUE(contains(names, "puck/side"));
  EXPECT_TRUE(contains(names, "pusher/table"));
  // Held: the puck's height does not move whatever pushes it; its x does.
  const std::vector<fesd::ContactPair> pairs = scene.allPairs();
  const auto model = scene.model(pairs);
  std::mt19937 random(3);
  const Eigen::VectorXd z =
      fesd_test::randomVector(model->velocity()->inputSize(), random, 0.1, 1.0);
  Eigen::VectorXd v(scene.stateSize());
  model->velocity()->evaluate(z.data(), v.data());
  EXPECT_EQ(v(scene.stateIndex(1) + 2), 0.0);
  EXPECT_NE(v(scene.stateIndex(1)), 0.0);
  const auto derivatives =
      checkAgainstFiniteDifferences(*model->velocity(), z, randomVector(scene.stateSize(), random));
  EXPECT_LT(derivatives.jacobian, kTolerance);
  EXPECT_LT(derivatives.hessian, kTolerance);
  // Within the tolerance it rests, beyond it floats.
  scene.bodies()[1].position.z() = 0.05 + 0.4e-3;
  EXPECT_EQ(scene.supportOf(1), 0);
  scene.bodies()[1].position.z() = 0.05 + 0.6e-3;
  EXPECT_EQ(scene.supportOf(1), -1);
  scene.bodies()[1].position.z() = 0.05;
  scene.bodies()[1].support = fesd::SupportMode::kNone;
  EXPECT_EQ(scene.supportOf(1), -1);
  EXPECT_TRUE(contains(pairNames(scene), "puck/table"));
  fesd::Scene planar(2);
  planar.bodies().push_back({"puck", 0.05, Eigen::Vector2d(0.0, 0.05), false});
  planar.walls().push_back({"floor", Eigen::Vector2d::UnitY(), 0.0});
  EXPECT_EQ(planar.supportOf(0), -1);
}

TEST(SceneSupports, LiftRatesAreTheHeldHeightsFreeVelocityForTheBodiesAPairTouches) {
  const fesd::Scene scene = tableScene();
  const std::vector<fesd::ContactPair> pairs = scene.allPairs();
  const fesd::SupportLiftRates lift = scene.supportLiftRates(pairs, {0, 1});
  ASSERT_EQ(lift.bodies, std::vector<int>{1});  // the pusher floats
  ASSERT_TRUE(lift.rates);
  // The puck's height rate in the model where it floats (its pairs with the table are last).
  fesd::Scene floating = scene;
  floating.bodies()[1].support = fesd::SupportMode::kNone;
  const auto free = floating.model(pairs);
  std::mt19937 random(5);
  const int nx = scene.stateSize(), nu = scene.controlSize();
  for (int trial = 0; trial < 3; ++trial) {
    Eigen::VectorXd z = fesd_test::randomVector(lift.rates->inputSize(), random, 0.1, 1.0);
    z.segment(nx, nu).setZero();
    Eigen::VectorXd rate(1), v(nx);
    lift.rates->evaluate(z.data(), rate.data());
    free->velocity()->evaluate(z.data(), v.data());
    EXPECT_NEAR(rate(0), v(scene.stateIndex(1) + 2), 1e-12);
    const auto derivatives = checkAgainstFiniteDifferences(*lift.rates, z, randomVector(1, random));
    EXPECT_LT(derivatives.jacobian, kTolerance);
    EXPECT_LT(derivatives.hessian, kTolerance);
  }
  // No pair of the puck: no rate to bound.
  std::vector<fesd::ContactPair> pusher_only;
  for (const fesd::ContactPair& pair : pairs) {
    if (scene.pairName(pair).rfind("pusher/", 0) == 0 && scene.pairName(pair) != "pusher/puck") {
      pusher_only.push_back(pair);
    }
  }
  ASSERT_FALSE(pusher_only.empty());
  EXPECT_FALSE(scene.supportLiftRates(pusher_only, {0, 1}).rates);
  EXPECT_FALSE(scene.supportLiftRates(pairs, {0}).rates);
}

}  // namespace
