// The DCS of centre pairs (scene/centre_pair_model.cpp): the velocity's Jacobian and the Hessian
// of w . v (which holds the third derivatives of the sphere centres) and the constraints'
// derivatives against central differences, for every pair kind, planar and spatial; a translating
// pair's derivatives without structural zeros.
#include <algorithm>
#include <memory>
#include <random>

#include <gtest/gtest.h>

#include "fesd_trajopt/scene/centre_pair_model.h"
#include "support/finite_differences.h"
#include "support/robot_files.h"

namespace {

using fesd::CentrePair;
using fesd::CollisionCentre;

/// A robot (q first) and two free bodies (the first actuated) with a pair of every kind: sphere
/// and body, sphere and sphere, sphere and point, sphere and wall, body and body, body and wall,
/// a body's offset sphere and a robot sphere.
fesd::CentrePairSystem mixedSystem(const std::string& robot_file, int dimension) {
  fesd::CentrePairSystem system;
  system.robot =
      std::make_shared<const fesd::KinematicModel>(fesd_test::loadShippedRobot(robot_file));
  system.dimension = dimension;
  const int nq = system.robot->numCoordinates();
  const int spheres = static_cast<int>(system.robot->spheres.size());
  system.state_size = nq + 2 * dimension;
  system.control_size = nq + dimension;
  for (int j = 0; j < nq; ++j) system.actuation.emplace_back(j, j);
  for (int d = 0; d < dimension; ++d) system.actuation.emplace_back(nq + d, nq + d);
  const CollisionCentre body0{CollisionCentre::Source::kFreeBody, nq};
  const CollisionCentre body1{CollisionCentre::Source::kFreeBody, nq + dimension};
  const CollisionCentre tip{CollisionCentre::Source::kRobotSphere, spheres - 1};
  const CollisionCentre middle{CollisionCentre::Source::kRobotSphere, spheres / 2};
  const CollisionCentre body0_sphere{CollisionCentre::Source::kFreeBody, nq,
                                     Eigen::Vector3d(0.1, -0.2, dimension == 3 ? 0.05 : 0.0)};
  const Eigen::Vector3d normal =
      Eigen::Vector3d(0.3, -0.5, dimension == 3 ? 0.8 : 0.0).normalized();
  system.pairs = {
      {CentrePair::Kind::kCentre, tip, body1, Eigen::Vector3d::Zero(), 0.01},
      {CentrePair::Kind::kCentre, middle, tip, Eigen::Vector3d::Zero(), 0.02},
      {CentrePair::Kind::kPoint, middle, {}, Eigen::Vector3d(0.2, 0.1, 0.3), 0.03},
      {CentrePair::Kind::kWall, tip, {}, normal, 0.1},
      {CentrePair::Kind::kCentre, body0, body1, Eigen::Vector3d::Zero(), 0.04},
      {CentrePair::Kind::kWall, body1, {}, normal, -0.2},
      {CentrePair::Kind::kCentre, body0_sphere, tip, Eigen::Vector3d::Zero(), 0.05},
  };
  system.constraint_scales = Eigen::VectorXd::Ones(system.pairs.size());
  return system;
}

class CentrePairDerivatives : public ::testing::TestWithParam<std::pair<const char*, int>> {};

TEST_P(CentrePairDerivatives, VelocityAndConstraintsAgainstFiniteDifferences) {
  const fesd::CentrePairSystem system = mixedSystem(GetParam().first, GetParam().second);
  const auto model = fesd::centrePairModel(system, "test");
  ASSERT_EQ(model->constraintSize(), 7);
  std::mt19937 random(41);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd z = fesd_test::randomVector(model->velocity()->inputSize(), random);
    const auto velocity = fesd_test::checkAgainstFiniteDifferences(
        *model->velocity(), z, fesd_test::randomVector(system.state_size, random));
    EXPECT_LT(velocity.jacobian, fesd_test::kTolerance);
    EXPECT_LT(velocity.hessian, fesd_test::kTolerance);
    const Eigen::VectorXd x = z.head(system.state_size);
    const auto constraints = fesd_test::checkAgainstFiniteDifferences(
        *model->constraints(), x, fesd_test::randomVector(7, random));
    EXPECT_LT(constraints.jacobian, fesd_test::kTolerance);
    EXPECT_LT(constraints.hessian, fesd_test::kTolerance);
    // The Hessian of w . v is not the quadratic model's constant: it holds third derivatives.
    const Eigen::VectorXd w = fesd_test::randomVector(system.state_size, random);
    EXPECT_GT(fesd_test::exactHessian(*model->velocity(), z, w)
                  .topLeftCorner(system.state_size, system.state_size)
                  .norm(),
              1e-3);
  }
}

INSTANTIATE_TEST_SUITE_P(Robots, CentrePairDerivatives,
                         ::testing::Values(std::make_pair("planar_arm.urdf", 2),
                                           std::make_pair("panda_spherized.urdf", 3)));

/// An actuated disc and two turning bodies (position and s = rho yaw each) with a pair of every
/// kind on a turning body's sphere: against the disc, the other body's sphere, a point, a wall.
fesd::CentrePairSystem turningSystem(int dimension) {
  fesd::CentrePairSystem system;
  system.dimension = dimension;
  const int body0 = dimension, body1 = 2 * dimension + 1;
  system.state_size = 3 * dimension + 2;
  system.control_size = dimension;
  for (int d = 0; d < dimension; ++d) system.actuation.emplace_back(d, d);
  const CollisionCentre disc{CollisionCentre::Source::kFreeBody, 0};
  const auto sphere = [&](int index, double x, double y, double rho) {
    return CollisionCentre{CollisionCentre::Source::kTurningBody, index, Eigen::Vector3d(x, y, 0.0),
                           rho};
  };
  const Eigen::Vector3d normal =
      Eigen::Vector3d(0.3, -0.5, dimension == 3 ? 0.8 : 0.0).normalized();
  system.pairs = {
      {CentrePair::Kind::kCentre, disc, sphere(body0, 0.4, 0.1, 0.5), Eigen::Vector3d::Zero(), 0.1},
      {CentrePair::Kind::kCentre, sphere(body0, -0.4, 0.1, 0.5), sphere(body1, 0.2, -0.3, 0.8),
       Eigen::Vector3d::Zero(), 0.2},
      {CentrePair::Kind::kPoint,
       sphere(body1, 0.2, -0.3, 0.8),
       {},
       Eigen::Vector3d(0.2, 0.1, 0.3),
       0.03},
      {CentrePair::Kind::kWall, sphere(body0, 0.4, 0.1, 0.5), {}, normal, 0.1},
  };
  system.constraint_scales = Eigen::VectorXd::Ones(system.pairs.size());
  return system;
}

TEST(CentrePairModel, TurningBodiesPairsAgainstFiniteDifferences) {
  std::mt19937 random(43);
  for (int dimension : {2, 3}) {
    SCOPED_TRACE(dimension);
    const fesd::CentrePairSystem system = turningSystem(dimension);
    const auto model = fesd::centrePairModel(system, "turning");
    for (int trial = 0; trial < 3; ++trial) {
      const Eigen::VectorXd z = fesd_test::randomVector(model->velocity()->inputSize(), random);
      const auto velocity = fesd_test::checkAgainstFiniteDifferences(
          *model->velocity(), z, fesd_test::randomVector(system.state_size, random));
      EXPECT_LT(velocity.jacobian, fesd_test::kTolerance);
      EXPECT_LT(velocity.hessian, fesd_test::kTolerance);
      const auto constraints = fesd_test::checkAgainstFiniteDifferences(
          *model->constraints(), z.head(system.state_size), fesd_test::randomVector(4, random));
      EXPECT_LT(constraints.jacobian, fesd_test::kTolerance);
      EXPECT_LT(constraints.hessian, fesd_test::kTolerance);
    }
  }
}

TEST(CentrePairModel, ValuesAreTheGeometricOnes) {
  const fesd::CentrePairSystem system = mixedSystem("planar_arm.urdf", 2);
  const auto model = fesd::centrePairModel(system, "test");
  Eigen::VectorXd x = Eigen::VectorXd::Zero(system.state_size);
  const int nq = 3;
  x.segment(nq, 2) << 1.0, 2.0;      // body 0
  x.segment(nq + 2, 2) << 0.5, 0.0;  // body 1
  Eigen::VectorXd c(7);
  model->constraints()->evaluate(x.data(), c.data());
  // At q = 0 the arm lies along x: its last sphere (hand/sphere_1) at 0.9.
  EXPECT_NEAR(c(0), 0.4 * 0.4 - 0.01, 1e-12);
  EXPECT_NEAR(c(4), 0.5 * 0.5 + 4.0 - 0.04, 1e-12);
  const Eigen::Vector3d n = system.pairs[3].point;
  EXPECT_NEAR(c(3), n.x() * 0.9 - 0.1, 1e-12);
  EXPECT_NEAR(c(5), n.x() * 0.5 + 0.2, 1e-12);  // body 1 against the wall
  // Body 0's sphere sits 0.1 right of and 0.2 below its position: at (1.1, 1.8).
  EXPECT_NEAR(c(6), 0.2 * 0.2 + 1.8 * 1.8 - 0.05, 1e-12);
}

TEST(CentrePairModel, TranslatingPairsCoupleOnlyTheSameCoordinate) {
  // Two free discs (state (x0, y0, x1, y1)), one against the other and one against the floor
  // y >= 0: c = |p0 - p1|^2 - 1 couples x0 with x1 and y0 with y1 only; the floor's
  // c = y0 - 0.5 depends on y0 alone and is linear.
  fesd::CentrePairSystem system;
  system.dimension = 2;
  system.state_size = 4;
  system.control_size = 2;
  system.actuation = {{0, 0}, {1, 1}};
  const CollisionCentre disc0{CollisionCentre::Source::kFreeBody, 0};
  const CollisionCentre disc1{CollisionCentre::Source::kFreeBody, 2};
  system.pairs.push_back({CentrePair::Kind::kCentre, disc0, disc1, Eigen::Vector3d::Zero(), 1.0});
  system.pairs.push_back({CentrePair::Kind::kWall, disc0, {}, Eigen::Vector3d::UnitY(), 0.5});
  system.constraint_scales = Eigen::Vector2d(2.0, 1.0);
  const auto model = fesd::centrePairModel(system, "discs");
  const fesd::SparsityPattern& jacobian = model->constraints()->jacobianPattern();
  EXPECT_EQ(jacobian.rows, (std::vector<int>{0, 0, 0, 0, 1}));
  EXPECT_EQ(jacobian.cols, (std::vector<int>{0, 1, 2, 3, 1}));
  const fesd::SparsityPattern& hessian = model->constraints()->hessianPattern();
  ASSERT_EQ(hessian.nonzeros(), 6);  // per coordinate (a, a), (b, b), (b, a)
  for (int e = 0; e < hessian.nonzeros(); ++e) {
    EXPECT_EQ(hessian.rows[e] % 2, hessian.cols[e] % 2) << "entry " << e;
  }
  // The velocity's x block: B u, and per coordinate the 2 x 2 block of lambda_0 Hess c_0.
  const fesd::SparsityPattern& velocity = model->velocity()->jacobianPattern();
  int x_block = 0;
  for (int e = 0; e < velocity.nonzeros(); ++e) x_block += velocity.cols[e] < 4;
  EXPECT_EQ(x_block, 8);
  EXPECT_EQ(velocity.nonzeros(), 2 + 8 + 4 + 1);  // B, curvature, lambda_0's column, lambda_1's
}

}  // namespace

namespace {

// A coordinate's mobility scales the contacts' share of its velocity (a robot's joints weighed by
// the reach squared), and 0 holds it (a support holding a body's height): its velocity is 0
// whatever the command and the forces, and its row is no entry of the patterns.
TEST(CentrePairModel, MobilityScalesTheContactTermsAndZeroHoldsACoordinate) {
  fesd::CentrePairSystem unit = mixedSystem("panda_spherized.urdf", 3);
  fesd::CentrePairSystem weighed = unit;
  const int nq = unit.robot->numCoordinates(), held = nq + 3 + 2;  // body1's z
  weighed.mobility.assign(unit.state_size, 1.0);
  for (int j = 0; j < nq; ++j) weighed.mobility[j] = 0.8;
  weighed.mobility[nq] = 0.5;
  weighed.mobility[held] = 0.0;
  const auto plain = fesd::centrePairModel(unit, "unit");
  const auto model = fesd::centrePairModel(weighed, "weighed");
  const int nx = unit.state_size, nu = unit.control_size;
  std::mt19937 random(43);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd z = fesd_test::randomVector(model->velocity()->inputSize(), random);
    const auto velocity = fesd_test::checkAgainstFiniteDifferences(
        *model->velocity(), z, fesd_test::randomVector(nx, random));
    EXPECT_LT(velocity.jacobian, fesd_test::kTolerance);
    EXPECT_LT(velocity.hessian, fesd_test::kTolerance);
    Eigen::VectorXd v(nx), v_plain(nx), forced(nx);
    model->velocity()->evaluate(z.data(), v.data());
    plain->velocity()->evaluate(z.data(), v_plain.data());
    Eigen::VectorXd commanded = z;  // the commands alone: no force
    commanded.tail(z.size() - nx - nu).setZero();
    plain->velocity()->evaluate(commanded.data(), forced.data());
    for (int i = 0; i < nx; ++i) {
      const double mobility = weighed.mobility[i];
      if (mobility == 0.0) {
        EXPECT_EQ(v(i), 0.0);
      } else {
        EXPECT_NEAR(v(i) - forced(i), mobility * (v_plain(i) - forced(i)), 1e-12) << i;
      }
    }
  }
  const fesd::SparsityPattern& pattern = model->velocity()->jacobianPattern();
  EXPECT_EQ(std::count(pattern.rows.begin(), pattern.rows.end(), held), 0);
  EXPECT_LT(pattern.nonzeros(), plain->velocity()->jacobianPattern().nonzeros());
}

TEST(CentrePairModel, HeldCoordinateRatesAreTheFreeVelocityAlongTheirDirections) {
  fesd::CentrePairSystem held = mixedSystem("panda_spherized.urdf", 3);
  const int nq = held.robot->numCoordinates(), body1_z = nq + 3 + 2, body0_y = nq + 1;
  held.mobility.assign(held.state_size, 1.0);
  held.mobility[body1_z] = held.mobility[body0_y] = 0.0;
  const auto rates = fesd::heldCoordinateRates(held, {{body1_z, 1.0}, {body0_y, -1.0}});
  const auto free = fesd::centrePairModel(mixedSystem("panda_spherized.urdf", 3), "free");
  ASSERT_EQ(rates->inputSize(), free->velocity()->inputSize());
  ASSERT_EQ(rates->outputSize(), 2);
  const int nx = held.state_size, nu = held.control_size;
  std::mt19937 random(47);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd z = fesd_test::randomVector(rates->inputSize(), random);
    const auto derivatives =
        fesd_test::checkAgainstFiniteDifferences(*rates, z, fesd_test::randomVector(2, random));
    EXPECT_LT(derivatives.jacobian, fesd_test::kTolerance);
    EXPECT_LT(derivatives.hessian, fesd_test::kTolerance);
    // The contacts' share of a free body's velocity: without the commands (body0 is actuated).
    Eigen::VectorXd forces_only = z;
    forces_only.segment(nx, nu).setZero();
    Eigen::VectorXd v(nx), r(2);
    free->velocity()->evaluate(forces_only.data(), v.data());
    rates->evaluate(z.data(), r.data());
    EXPECT_NEAR(r(0), v(body1_z), 1e-12);
    EXPECT_NEAR(r(1), -v(body0_y), 1e-12);
  }
  // Only the held rows' entries: the pairs' forces on those coordinates.
  const fesd::SparsityPattern& pattern = rates->jacobianPattern();
  for (int e = 0; e < pattern.nonzeros(); ++e) EXPECT_LT(pattern.rows[e], 2);
  EXPECT_LT(pattern.nonzeros(), free->velocity()->jacobianPattern().nonzeros() / 4);
}

}  // namespace

namespace {

/// Values, Jacobian and Hessian of a function and of another at z, bit for bit.
void expectSameBits(const fesd::SmoothFunction& a, const fesd::SmoothFunction& b,
                    const Eigen::VectorXd& z, const Eigen::VectorXd& w) {
  Eigen::VectorXd ya(a.outputSize()), yb(b.outputSize());
  a.evaluate(z.data(), ya.data());
  b.evaluate(z.data(), yb.data());
  EXPECT_TRUE((ya.array() == yb.array()).all());
  std::vector<double> ja(a.jacobianPattern().nonzeros()), jb(ja.size());
  a.evaluateJacobian(z.data(), ja.data());
  b.evaluateJacobian(z.data(), jb.data());
  EXPECT_EQ(ja, jb);
  std::vector<double> ha(a.hessianPattern().nonzeros()), hb(ha.size());
  a.evaluateHessian(z.data(), w.data(), ha.data());
  b.evaluateHessian(z.data(), w.data(), hb.data());
  EXPECT_EQ(ha, hb);
}

}  // namespace

/// Another thread's copies of a model's velocity and constraints: their own kinematics (one
/// copy for both, as the originals share theirs), the same bits as the originals, evaluated
/// alternately with them at other states.
TEST(CentrePairModel, ThreadCopiesShareTheirOwnKinematicsAndGiveTheSameBits) {
  const fesd::CentrePairSystem system = mixedSystem("panda_spherized.urdf", 3);
  const auto model = fesd::centrePairModel(system, "test");
  fesd::ThreadCopies copies;
  const auto velocity = copies.function(model->velocity());
  const auto constraints = copies.function(model->constraints());
  ASSERT_NE(velocity, model->velocity());
  ASSERT_NE(constraints, model->constraints());
  std::mt19937 random(5);
  for (int trial = 0; trial < 4; ++trial) {
    const Eigen::VectorXd z = fesd_test::randomVector(velocity->inputSize(), random);
    const Eigen::VectorXd other = fesd_test::randomVector(velocity->inputSize(), random);
    double ignored[16];
    model->constraints()->evaluate(other.data(), ignored);  // the originals elsewhere
    expectSameBits(*model->velocity(), *velocity, z,
                   fesd_test::randomVector(system.state_size, random));
    expectSameBits(*model->constraints(), *constraints, z.head(system.state_size),
                   fesd_test::randomVector(7, random));
  }
}
