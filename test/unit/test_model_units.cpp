// A robot in other length units (kinematics/model_units.cpp): the same robot with its lengths
// scaled puts every sphere where the original does, scaled; in a solve's units (every coordinate
// a length) its centres are the original's divided by L at q / L, with the same Jacobian, and
// inverse kinematics finds the original's joints divided by L. On a robot with every joint kind.
#include "fesd_trajopt/kinematics/model_units.h"

#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "fesd_trajopt/kinematics/inverse_kinematics.h"
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

TEST(ModelUnits, InLengthUnitsEveryCoordinateScalesWithTheCentresAndTheJacobianStays) {
  const fesd::KinematicModel model = mixedRobot();
  const double length = 0.04;
  const fesd::KinematicModel scaled = fesd::inLengthUnits(model, length);
  for (int j = 0; j < model.numCoordinates(); ++j) {
    EXPECT_DOUBLE_EQ(scaled.joints[j].coordinate_scale, isPrismatic(model, j) ? 1.0 : length);
    if (std::isfinite(model.joints[j].upper)) {
      EXPECT_NEAR(scaled.joints[j].upper, model.joints[j].upper / length,
                  1e-14 * scaled.joints[j].upper);
    }
    EXPECT_NEAR(scaled.joints[j].max_velocity, model.joints[j].max_velocity / length,
                1e-14 * scaled.joints[j].max_velocity);
  }
  std::mt19937 random(8);
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = fesd_test::randomVector(model.numCoordinates(), random);
    fesd::KinematicData data, data_scaled;
    fesd::forwardKinematics(model, q, data);
    fesd::forwardKinematics(scaled, q / length, data_scaled);
    for (int s = 0; s < static_cast<int>(model.spheres.size()); ++s) {
      EXPECT_LT((length * data_scaled.sphere_centres[s] - data.sphere_centres[s]).norm(), 1e-13);
      // dp~/dq~ = (1 / L) dp/dq L: the same numbers.
      EXPECT_LT(
          (fesd::sphereJacobian(scaled, data_scaled, s) - fesd::sphereJacobian(model, data, s))
              .cwiseAbs()
              .maxCoeff(),
          1e-12);
      const auto centre = [&](const Eigen::VectorXd& at) -> Eigen::VectorXd {
        fesd::KinematicData moved;
        fesd::forwardKinematics(scaled, at, moved);
        return moved.sphere_centres[s];
      };
      EXPECT_LT((fesd::sphereJacobian(scaled, data_scaled, s) -
                 fesd_test::finiteDifferenceJacobian(centre, q / length))
                    .cwiseAbs()
                    .maxCoeff(),
                fesd_test::kTolerance);
    }
  }
}

// Its steps are bounded in radians, not in units of its coordinates, so that it takes the
// original's path, scaled.
TEST(ModelUnits, InverseKinematicsInLengthUnitsFindsTheOriginalJointsScaled) {
  const fesd::KinematicModel panda = fesd_test::loadShippedRobot("panda_spherized.urdf");
  const double length = 0.05;
  const fesd::KinematicModel scaled = fesd::inLengthUnits(panda, length);
  const int finger = panda.sphereIndex("panda_leftfinger/sphere_1");
  Eigen::VectorXd ready(7);
  ready << 0.0, -0.785, 0.0, -2.356, 0.0, 1.571, 0.785;
  const Eigen::Vector3d target(0.5, 0.2, 0.3);
  const fesd::InverseKinematicsResult original =
      fesd::sphereInverseKinematics(panda, finger, target, ready);
  fesd::InverseKinematicsOptions options;
  options.tolerance = 1e-10 / length;
  const fesd::InverseKinematicsResult result =
      fesd::sphereInverseKinematics(scaled, finger, target / length, ready / length, options);
  EXPECT_TRUE(original.reached);
  EXPECT_TRUE(result.reached);
  EXPECT_EQ(result.iterations, original.iterations);
  EXPECT_LT((length * result.q - original.q).cwiseAbs().maxCoeff(), 1e-9);
}

}  // namespace
