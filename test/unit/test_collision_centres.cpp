// Collision centres (scene/collision_centres.cpp): a robot sphere's and a turning body's sphere's
// centre and their first, second and third derivatives in their variables against central
// differences, a free body's centre as the state itself, and the plane's projection.
#include <memory>
#include <random>
#include <vector>

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include "fesd_trajopt/scene/collision_centres.h"
#include "support/finite_differences.h"
#include "support/robot_files.h"

namespace {

using fesd::CentreEvaluator;
using fesd::CollisionCentre;

std::shared_ptr<const fesd::KinematicModel> panda() {
  return std::make_shared<const fesd::KinematicModel>(
      fesd_test::loadShippedRobot("panda_spherized.urdf"));
}

// The evaluator's derivatives as values (it writes them into buffers its callers keep).
Eigen::Matrix3Xd jacobianOf(const CentreEvaluator& e, const CollisionCentre& centre) {
  Eigen::Matrix3Xd into;
  e.jacobian(centre, into);
  return into;
}
Eigen::MatrixXd weightedHessianOf(const CentreEvaluator& e, const CollisionCentre& centre,
                                  const Eigen::Vector3d& w) {
  Eigen::MatrixXd into;
  e.weightedHessian(centre, w, into);
  return into;
}
Eigen::MatrixXd thirdDerivativeOf(const CentreEvaluator& e, const CollisionCentre& centre,
                                  const Eigen::Vector3d& w, const Eigen::VectorXd& v) {
  Eigen::MatrixXd into;
  e.weightedThirdDerivative(centre, w, v, into);
  return into;
}

/// x with q in [-1, 1] and one free body after the robot's coordinates.
Eigen::VectorXd randomState(int nq, std::mt19937& random) {
  return fesd_test::randomVector(nq + 3, random);
}

/// A centre's position, Jacobian, weighted Hessian and its derivative along v at x against
/// central differences in the centre's local variables (everything else held at x).
void expectDerivativesMatchDifferences(const std::shared_ptr<const fesd::KinematicModel>& robot,
                                       int dimension, const CollisionCentre& centre,
                                       const Eigen::VectorXd& x, std::mt19937& random) {
  CentreEvaluator evaluator(robot, dimension);
  const std::vector<int> variables = evaluator.variables(centre);
  const Eigen::Vector3d w = fesd_test::randomVector(3, random);
  const Eigen::VectorXd v = fesd_test::randomVector(static_cast<int>(variables.size()), random);
  const auto at = [&](const Eigen::VectorXd& local) {
    Eigen::VectorXd moved = x;
    for (size_t i = 0; i < variables.size(); ++i) moved(variables[i]) = local(i);
    return moved;
  };
  Eigen::VectorXd local(variables.size());
  for (size_t i = 0; i < variables.size(); ++i) local(i) = x(variables[i]);
  const auto position = [&](const Eigen::VectorXd& l) -> Eigen::VectorXd {
    const Eigen::VectorXd moved = at(l);
    CentreEvaluator e(robot, dimension);
    e.setState(moved.data());
    return e.position(centre);
  };
  const auto weighted_gradient = [&](const Eigen::VectorXd& l) -> Eigen::VectorXd {
    const Eigen::VectorXd moved = at(l);
    CentreEvaluator e(robot, dimension);
    e.setState(moved.data());
    return jacobianOf(e, centre).transpose() * w;
  };
  const auto hessian_along_v = [&](const Eigen::VectorXd& l) -> Eigen::VectorXd {
    const Eigen::VectorXd moved = at(l);
    CentreEvaluator e(robot, dimension);
    e.setState(moved.data());
    return weightedHessianOf(e, centre, w) * v;
  };
  evaluator.setState(x.data());
  const Eigen::MatrixXd jacobian = jacobianOf(evaluator, centre);
  EXPECT_LT((jacobian - fesd_test::finiteDifferenceJacobian(position, local)).norm(), 1e-7);
  const Eigen::MatrixXd hessian = weightedHessianOf(evaluator, centre, w);
  EXPECT_LT((hessian - fesd_test::finiteDifferenceJacobian(weighted_gradient, local)).norm(), 1e-7);
  // d/dx (H[w] v) = T[w, v] (symmetric in its indices): column k of the difference quotient of
  // H[w] v is T[w, e_k] v, which equals T[w, v] e_k.
  const Eigen::MatrixXd third = thirdDerivativeOf(evaluator, centre, w, v);
  EXPECT_LT((third - fesd_test::finiteDifferenceJacobian(hessian_along_v, local)).norm(), 1e-7);
  EXPECT_GT(third.norm(), 1e-3);  // something to compare
}

TEST(CollisionCentres, RobotSphereDerivativesAgainstFiniteDifferences) {
  const auto robot = panda();
  const int nq = robot->numCoordinates();
  std::mt19937 random(5);
  // Spheres on the third link and below, off their joints' axes: every derivative is nonzero.
  for (int sphere : {20, 40, static_cast<int>(robot->spheres.size()) - 1}) {
    SCOPED_TRACE(robot->spheres[sphere].name);
    const CollisionCentre centre{CollisionCentre::Source::kRobotSphere, sphere};
    ASSERT_GE(robot->chainOf(sphere).size(), 3u);
    expectDerivativesMatchDifferences(robot, 3, centre, randomState(nq, random), random);
  }
}

/// A turning body's sphere: p = position + R(s / rho) offset, about z, in the plane and in space.
TEST(CollisionCentres, TurningBodySphereTurnsWithItsYawAndItsDerivativesMatchDifferences) {
  std::mt19937 random(9);
  const Eigen::Vector3d offset(0.3, -0.4, 0.2);
  const double rho = 0.7;
  for (int dimension : {2, 3}) {
    SCOPED_TRACE(dimension);
    const CollisionCentre centre{CollisionCentre::Source::kTurningBody, 1, offset, rho};
    const Eigen::VectorXd x = fesd_test::randomVector(dimension + 2, random);  // x(0): another
    CentreEvaluator evaluator(nullptr, dimension);
    std::vector<int> expected_variables;
    for (int d = 0; d <= dimension; ++d) expected_variables.push_back(1 + d);
    EXPECT_EQ(evaluator.variables(centre), expected_variables);
    evaluator.setState(x.data());
    const double yaw = x(1 + dimension) / rho;
    Eigen::Vector3d expected = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * offset;
    expected.head(dimension) += x.segment(1, dimension);
    if (dimension == 2) expected.z() = 0.0;
    EXPECT_LT((evaluator.position(centre) - expected).norm(), 1e-15);
    expectDerivativesMatchDifferences(nullptr, dimension, centre, x, random);
  }
}

// The evaluator keeps the kinematics of the configurations it has seen: returning to one, and
// running past the number it keeps, gives exactly what a fresh evaluator computes there.
TEST(CollisionCentres, KeptConfigurationsGiveTheBitsOfAFreshEvaluation) {
  const auto robot = panda();
  const int nq = robot->numCoordinates();
  std::mt19937 random(8);
  const CollisionCentre centre{CollisionCentre::Source::kRobotSphere, 40};
  const Eigen::Vector3d w = fesd_test::randomVector(3, random);
  const int local = static_cast<int>(robot->chainOf(centre.index).size());
  const Eigen::VectorXd v = fesd_test::randomVector(local, random);
  std::vector<Eigen::VectorXd> states;
  for (size_t k = 0; k < CentreEvaluator::kKinematicsKept + 5; ++k) {
    states.push_back(randomState(nq, random));
  }
  const auto same = [&](const CentreEvaluator& evaluator, const Eigen::VectorXd& x) {
    CentreEvaluator fresh(robot, 3);
    fresh.setState(x.data());
    return evaluator.position(centre) == fresh.position(centre) &&
           jacobianOf(evaluator, centre) == jacobianOf(fresh, centre) &&
           weightedHessianOf(evaluator, centre, w) == weightedHessianOf(fresh, centre, w) &&
           thirdDerivativeOf(evaluator, centre, w, v) == thirdDerivativeOf(fresh, centre, w, v);
  };
  CentreEvaluator evaluator(robot, 3);
  int mismatches = 0;
  for (int pass = 0; pass < 2; ++pass) {  // the second pass finds the first's kept or forgotten
    for (size_t k = 0; k < states.size(); k += pass == 0 ? 1 : 97) {
      evaluator.setState(states[k].data());
      mismatches += !same(evaluator, states[k]);
      evaluator.setState(states[0].data());  // back to a kept one between two new ones
      mismatches += !same(evaluator, states[0]);
    }
  }
  EXPECT_EQ(mismatches, 0);
}

TEST(CollisionCentres, FreeBodyIsItsStateItsSpheresOffsetAndPlanarScenesDropZ) {
  const auto robot = panda();
  const int nq = robot->numCoordinates();
  std::mt19937 random(6);
  const Eigen::VectorXd x = randomState(nq, random);
  const CollisionCentre body{CollisionCentre::Source::kFreeBody, nq};
  CentreEvaluator spatial(robot, 3), planar(robot, 2);
  spatial.setState(x.data());
  planar.setState(x.data());
  EXPECT_EQ(spatial.position(body), Eigen::Vector3d(x.tail(3)));
  EXPECT_EQ(spatial.variables(body), (std::vector<int>{nq, nq + 1, nq + 2}));
  EXPECT_EQ(planar.variables(body), (std::vector<int>{nq, nq + 1}));
  EXPECT_EQ(planar.position(body), Eigen::Vector3d(x(nq), x(nq + 1), 0.0));
  const CollisionCentre sphere{CollisionCentre::Source::kRobotSphere, 30};
  EXPECT_EQ(planar.position(sphere).z(), 0.0);
  EXPECT_EQ(jacobianOf(planar, sphere).row(2).norm(), 0.0);
  EXPECT_EQ(planar.position(sphere).head(2), spatial.position(sphere).head(2));
  EXPECT_EQ(weightedHessianOf(spatial, body, Eigen::Vector3d::Ones()).norm(), 0.0);
  // A free body's sphere translates with it: its centre is offset, its derivatives the body's.
  const CollisionCentre sphere_of_body{CollisionCentre::Source::kFreeBody, nq,
                                       Eigen::Vector3d(0.1, -0.2, 0.3)};
  EXPECT_TRUE(spatial.position(sphere_of_body)
                  .isApprox(Eigen::Vector3d(x.tail(3)) + Eigen::Vector3d(0.1, -0.2, 0.3), 1e-15));
  EXPECT_EQ(planar.position(sphere_of_body), Eigen::Vector3d(x(nq) + 0.1, x(nq + 1) - 0.2, 0.0));
  EXPECT_EQ(jacobianOf(spatial, sphere_of_body), jacobianOf(spatial, body));
  EXPECT_EQ(planar.variables(sphere_of_body), planar.variables(body));
}

}  // namespace
