// A robot in other length units (kinematics/model_units.cpp): the same robot with its lengths
// scaled puts every sphere where the original does, scaled; in a solve's units (every coordinate
// a length: a revolute joint's the arc at the robot's reach) its centres are the original's
// divided by L, its reach 1, and inverse kinematics finds the original's joints. On a robot with
// every joint kind and on the Panda.
#include "fesd_trajopt/kinematics/model_units.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "fesd_trajopt/kinematics/inverse_kinematics.h"
#include "fesd_trajopt/kinematics/reach.h"
#include "support/finite_differences.h"
#include "support/robot_files.h"

namespace {

fesd::KinematicModel mixedRobot() {
  fesd::KinematicModelResult built = fesd::buildKinematicModel(fesd_test::mixedJointsUrdf());
  EXPECT_EQ(built.error, "");
  return built.model;
}

bool isPrismatic(const fesd::KinematicModel& model, int joint) {
  return model.joints[joint].type == fesd::JointType::kPrismatic;
}

TEST(ModelUnits, ScaledLengthsPutEverySphereWhereTheOriginalDoesScaled) {
  const fesd::KinematicModel model = mixedRobot();
  const double factor = 1000.0;  // the robot in millimetres
  const fesd::KinematicModel millimetres = fesd::withLengthsScaled(model, factor);
  std::mt19937 random(3);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd q = fesd_test::randomVector(model.numCoordinates(), random);
    Eigen::VectorXd q_mm = q;
    for (int j = 0; j < q.size(); ++j) {
      if (isPrismatic(model, j)) q_mm(j) *= factor;  // angles stay radians
    }
    fesd::KinematicData data, data_mm;
    fesd::forwardKinematics(model, q, data);
    fesd::forwardKinematics(millimetres, q_mm, data_mm);
    for (size_t s = 0; s < model.spheres.size(); ++s) {
      EXPECT_LT((data_mm.sphere_centres[s] - factor * data.sphere_centres[s]).norm(),
                1e-12 * factor);
      EXPECT_DOUBLE_EQ(millimetres.spheres[s].radius, factor * model.spheres[s].radius);
    }
  }
  const int slide = model.jointIndex("slide");
  EXPECT_DOUBLE_EQ(millimetres.joints[slide].upper, 0.5 * factor);
  EXPECT_DOUBLE_EQ(millimetres.joints[slide].max_velocity, 0.2 * factor);
  EXPECT_EQ(millimetres.joints[model.jointIndex("turn")].upper, 2.0);
}

TEST(ModelUnits, InLengthUnitsEveryCoordinateIsALengthAndTheReachIsOne) {
  const fesd::KinematicModel model = mixedRobot();
  const double length = 0.04, reach = fesd::robotReach(model);
  const fesd::KinematicModel scaled = fesd::inLengthUnits(model, length);
  EXPECT_NEAR(fesd::robotReach(scaled), 1.0, 1e-15);
  // Per unit of a coordinate: a revolute joint turns L / reach radians, a prismatic one moves L.
  Eigen::VectorXd units(model.numCoordinates());
  for (int j = 0; j < model.numCoordinates(); ++j) {
    units(j) = isPrismatic(model, j) ? length : length / reach;
    EXPECT_NEAR(scaled.joints[j].coordinate_scale, isPrismatic(model, j) ? 1.0 : units(j), 1e-16);
    if (std::isfinite(model.joints[j].upper)) {
      EXPECT_NEAR(scaled.joints[j].upper, model.joints[j].upper / units(j),
                  1e-14 * scaled.joints[j].upper);
    }
    EXPECT_NEAR(scaled.joints[j].max_velocity, model.joints[j].max_velocity / units(j),
                1e-14 * scaled.joints[j].max_velocity);
  }
  std::mt19937 random(8);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = fesd_test::randomVector(model.numCoordinates(), random);
    const Eigen::VectorXd q_scaled = q.cwiseQuotient(units);
    fesd::KinematicData data, data_scaled;
    fesd::forwardKinematics(model, q, data);
    fesd::forwardKinematics(scaled, q_scaled, data_scaled);
    for (int s = 0; s < static_cast<int>(model.spheres.size()); ++s) {
      EXPECT_LT((length * data_scaled.sphere_centres[s] - data.sphere_centres[s]).norm(), 1e-13);
      // dp~/dq~ = (1 / L) dp/dq unit.
      EXPECT_LT((length * fesd::sphereJacobian(scaled, data_scaled, s) -
                 fesd::sphereJacobian(model, data, s) * units.asDiagonal())
                    .cwiseAbs()
                    .maxCoeff(),
                1e-14);
      const auto centre = [&](const Eigen::VectorXd& at) -> Eigen::VectorXd {
        fesd::KinematicData moved;
        fesd::forwardKinematics(scaled, at, moved);
        return moved.sphere_centres[s];
      };
      EXPECT_LT((fesd::sphereJacobian(scaled, data_scaled, s) -
                 fesd_test::finiteDifferenceJacobian(centre, q_scaled))
                    .cwiseAbs()
                    .maxCoeff(),
                fesd_test::kTolerance);
    }
  }
}

// In a solve's units it reaches what it reaches in the original's: its step bound in radians,
// its tolerance in units of L. (A redundant arm may end elsewhere in its null space: the
// Jacobian in these coordinates is the original's over the reach, so the damping weighs
// differently.)
TEST(ModelUnits, InverseKinematicsInLengthUnitsReachesTheOriginalsTarget) {
  const fesd::KinematicModel panda = fesd_test::loadShippedRobot("panda_spherized.urdf");
  const double length = 0.05, unit = length / fesd::robotReach(panda);  // radians per unit
  const fesd::KinematicModel scaled = fesd::inLengthUnits(panda, length);
  const int finger = panda.sphereIndex("panda_leftfinger/sphere_1");
  Eigen::VectorXd ready(7);
  ready << 0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785;
  const Eigen::Vector3d target(0.5, 0.2, 0.3);
  fesd::InverseKinematicsOptions options;
  options.tolerance = 1e-10 / length;
  const fesd::InverseKinematicsResult result =
      fesd::sphereInverseKinematics(scaled, finger, target / length, ready / unit, options);
  EXPECT_TRUE(result.reached);
  fesd::KinematicData data;
  fesd::forwardKinematics(panda, unit * result.q, data);
  EXPECT_LT((data.sphere_centres[finger] - target).norm(), 1e-9);
  for (int j = 0; j < panda.numCoordinates(); ++j) {
    EXPECT_LE(unit * result.q(j), panda.joints[j].upper + 1e-12);
    EXPECT_GE(unit * result.q(j), panda.joints[j].lower - 1e-12);
  }
}

}  // namespace
