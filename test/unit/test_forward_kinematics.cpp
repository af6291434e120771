// Forward kinematics and the exact derivatives of sphere centres
// (kinematics/forward_kinematics.cpp): frames, centres and Jacobians against orocos KDL on the
// shipped robots and a robot with every joint kind, Jacobians against central differences.
#include <algorithm>
#include <cstdio>
#include <random>
#include <string>

#include <gtest/gtest.h>
#include <kdl/chainfksolverpos_recursive.hpp>
#include <kdl/chainjnttojacsolver.hpp>
#include <kdl_parser/kdl_parser.hpp>

#include "fesd_trajopt/kinematics/forward_kinematics.h"
#include "support/finite_differences.h"
#include "support/robot_files.h"

namespace {

using fesd::KinematicData;
using fesd::KinematicModel;

/// The URDFs every test here runs on.
std::string robotUrdf(const std::string& robot) {
  return robot == "mixed" ? fesd_test::mixedJointsUrdf() : fesd_test::readRobotFile(robot);
}

KinematicModel buildModel(const std::string& urdf) {
  fesd::KinematicModelResult result = fesd::buildKinematicModel(urdf);
  EXPECT_EQ(result.error, "");
  return std::move(result.model);
}

/// A configuration inside the limits (continuous joints within [-pi, pi]).
Eigen::VectorXd randomConfiguration(const KinematicModel& model, std::mt19937& random) {
  Eigen::VectorXd q(model.numCoordinates());
  for (int j = 0; j < q.size(); ++j) {
    const double lower = std::max(model.joints[j].lower, -M_PI);
    const double upper = std::min(model.joints[j].upper, M_PI);
    q(j) = std::uniform_real_distribution<double>(lower, upper)(random);
  }
  return q;
}

/// Largest |exact - approximate| relative to max(1, |exact|).
double relativeError(const Eigen::MatrixXd& exact, const Eigen::MatrixXd& approximate) {
  return ((exact - approximate).array().abs() / exact.array().abs().max(1.0)).maxCoeff();
}

Eigen::Matrix4d toMatrix(const KDL::Frame& frame) {
  Eigen::Matrix4d m = Eigen::Matrix4d::Identity();
  for (int r = 0; r < 3; ++r) {
    for (int c = 0; c < 3; ++c) m(r, c) = frame.M(r, c);
    m(r, 3) = frame.p(r);
  }
  return m;
}

class KinematicsOnRobots : public ::testing::TestWithParam<std::string> {};

TEST_P(KinematicsOnRobots, FramesCentresAndJacobiansAgreeWithKdl) {
  const std::string urdf = robotUrdf(GetParam());
  const KinematicModel model = buildModel(urdf);
  KDL::Tree tree;
  ASSERT_TRUE(kdl_parser::treeFromString(urdf, tree));
  std::mt19937 random(7);
  KinematicData data;
  double frame_error = 0.0, centre_error = 0.0, jacobian_error = 0.0;
  for (int trial = 0; trial < 5; ++trial) {
    const Eigen::VectorXd q = randomConfiguration(model, random);
    fesd::forwardKinematics(model, q, data);
    for (std::size_t s = 0; s < model.spheres.size(); ++s) {
      const fesd::KinematicSphere& sphere = model.spheres[s];
      KDL::Chain chain;
      ASSERT_TRUE(tree.getChain(model.root_link, model.links[sphere.link].name, chain));
      // KDL's joint order along the chain, mapped to ours.
      KDL::JntArray joints(chain.getNrOfJoints());
      std::vector<int> ours;
      for (const KDL::Segment& segment : chain.segments) {
        if (segment.getJoint().getType() == KDL::Joint::None) continue;
        ours.push_back(model.jointIndex(segment.getJoint().getName()));
        ASSERT_GE(ours.back(), 0);
        joints(ours.size() - 1) = q(ours.back());
      }
      KDL::Frame link_frame;
      ASSERT_GE(KDL::ChainFkSolverPos_recursive(chain).JntToCart(joints, link_frame), 0);
      frame_error = std::max(
          frame_error, (toMatrix(link_frame) - fesd::linkFrame(model, data, sphere.link).matrix())
                           .cwiseAbs()
                           .maxCoeff());
      // The sphere centre as a last fixed segment, so that KDL's Jacobian refers to it.
      const Eigen::Vector3d& c = sphere.local_centre;
      chain.addSegment(
          KDL::Segment(KDL::Joint(KDL::Joint::None), KDL::Frame(KDL::Vector(c.x(), c.y(), c.z()))));
      KDL::Frame centre;
      ASSERT_GE(KDL::ChainFkSolverPos_recursive(chain).JntToCart(joints, centre), 0);
      for (int r = 0; r < 3; ++r) {
        centre_error = std::max(centre_error, std::abs(centre.p(r) - data.sphere_centres[s](r)));
      }
      KDL::Jacobian kdl_jacobian(chain.getNrOfJoints());
      ASSERT_GE(KDL::ChainJntToJacSolver(chain).JntToJac(joints, kdl_jacobian), 0);
      Eigen::Matrix3Xd expected = Eigen::Matrix3Xd::Zero(3, model.numCoordinates());
      for (std::size_t k = 0; k < ours.size(); ++k) {
        expected.col(ours[k]) = kdl_jacobian.data.block<3, 1>(0, k);
      }
      jacobian_error = std::max(
          jacobian_error, (expected - fesd::sphereJacobian(model, data, s)).cwiseAbs().maxCoeff());
    }
  }
  std::printf("[ KDL      ] %s: frames %.1e, centres %.1e, Jacobians %.1e\n", GetParam().c_str(),
              frame_error, centre_error, jacobian_error);
  EXPECT_LT(frame_error, 1e-12);
  EXPECT_LT(centre_error, 1e-12);
  EXPECT_LT(jacobian_error, 1e-12);
}

TEST_P(KinematicsOnRobots, JacobiansMatchCentralDifferences) {
  const KinematicModel model = buildModel(robotUrdf(GetParam()));
  std::mt19937 random(11);
  double first = 0.0;
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd q = randomConfiguration(model, random);
    KinematicData data;
    fesd::forwardKinematics(model, q, data);
    for (int s = 0; s < static_cast<int>(model.spheres.size()); ++s) {
      const auto centre = [&](const Eigen::VectorXd& p) -> Eigen::VectorXd {
        KinematicData shifted;
        fesd::forwardKinematics(model, p, shifted);
        return shifted.sphere_centres[s];
      };
      first = std::max(first, relativeError(fesd::sphereJacobian(model, data, s),
                                            fesd_test::finiteDifferenceJacobian(centre, q)));
    }
  }
  std::printf("[ FD       ] %s: Jacobians %.1e\n", GetParam().c_str(), first);
  EXPECT_LT(first, fesd_test::kTolerance);
}

INSTANTIATE_TEST_SUITE_P(ForwardKinematics, KinematicsOnRobots,
                         ::testing::Values("planar_arm.urdf", "panda_spherized.urdf", "mixed"),
                         [](const ::testing::TestParamInfo<std::string>& info) {
                           return info.param == "planar_arm.urdf"        ? std::string("PlanarArm")
                                  : info.param == "panda_spherized.urdf" ? std::string("Panda")
                                                                         : std::string("Mixed");
                         });

}  // namespace
