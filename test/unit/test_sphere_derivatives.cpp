// A sphere centre's chain derivatives computed once per configuration
// (kinematics/sphere_derivatives.cpp): against the same formulas evaluated entry by entry
// (support/naive_kinematics.h) to the bit, and against central differences, on the shipped robots
// and a robot with every joint kind.
#include "fesd_trajopt/kinematics/sphere_derivatives.h"

#include <algorithm>
#include <random>
#include <string>
#include <utility>

#include <gtest/gtest.h>

#include "fesd_trajopt/kinematics/model_units.h"
#include "support/finite_differences.h"
#include "support/naive_kinematics.h"
#include "support/robot_files.h"

namespace {

using fesd::KinematicModel;

/// A shipped robot's model, or the robot with every joint kind ("mixed"); "<name>@L": in units
/// of L (inLengthUnits: its joints turn L radians per unit).
KinematicModel robot(const std::string& name) {
  const size_t at = name.find('@');
  const std::string file = name.substr(0, at);
  fesd::KinematicModelResult built = fesd::buildKinematicModel(
      file == "mixed" ? fesd_test::mixedJointsUrdf() : fesd_test::readRobotFile(file));
  EXPECT_EQ(built.error, "");
  if (at == std::string::npos) return std::move(built.model);
  return fesd::inLengthUnits(built.model, std::stod(name.substr(at + 1)));
}

class SphereDerivativesOnRobots : public ::testing::TestWithParam<std::string> {};

TEST_P(SphereDerivativesOnRobots, EqualTheEntryByEntryFormulas) {
  const KinematicModel model = robot(GetParam());
  const int nq = model.numCoordinates();
  std::mt19937 random(17);
  fesd::SphereDerivatives derivatives;  // reused across spheres of different chain lengths
  double largest = 0.0, third_norm = 0.0;
  int compared = 0;
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd q = fesd_test::randomVector(nq, random);
    const Eigen::Vector3d w = fesd_test::randomVector(3, random);
    fesd::KinematicData data;
    fesd::forwardKinematics(model, q, data);
    for (int s = 0; s < static_cast<int>(model.spheres.size()); ++s) {
      const std::vector<int>& chain = model.chainOf(s);
      const int n = static_cast<int>(chain.size());
      derivatives.compute(model, data, s);
      ASSERT_EQ(derivatives.size(), n);
      const Eigen::VectorXd v_local = fesd_test::randomVector(n, random);
      Eigen::VectorXd v = Eigen::VectorXd::Zero(nq);
      for (int a = 0; a < n; ++a) v(chain[a]) = v_local(a);
      const Eigen::MatrixXd hessian = fesd_test::weightedSphereHessian(model, data, s, w);
      const Eigen::MatrixXd third = fesd_test::weightedSphereThirdDerivative(model, data, s, w, v);
      Eigen::MatrixXd local_hessian, local_third;
      derivatives.weightedHessian(w, local_hessian);
      derivatives.weightedThirdDerivative(w, v_local, local_third);
      for (int a = 0; a < n; ++a) {
        largest = std::max(largest, (derivatives.jacobian().col(a) -
                                     fesd::sphereJacobianColumn(model, data, s, chain[a]))
                                        .cwiseAbs()
                                        .maxCoeff());
        for (int b = 0; b < n; ++b) {
          largest = std::max({largest,
                              (derivatives.second(a, b) - fesd_test::sphereSecondDerivative(
                                                              model, data, s, chain[a], chain[b]))
                                  .cwiseAbs()
                                  .maxCoeff(),
                              std::fabs(local_hessian(a, b) - hessian(chain[a], chain[b])),
                              std::fabs(local_third(a, b) - third(chain[a], chain[b]))});
          third_norm = std::max(third_norm, std::fabs(third(chain[a], chain[b])));
          ++compared;
        }
      }
    }
  }
  EXPECT_GT(compared, 0);
  EXPECT_GT(third_norm, 1e-2);            // something to compare
  EXPECT_EQ(largest, 0.0) << GetParam();  // the same formulas, summed in the same order
}

// The Jacobian's derivative in q is the second derivative, and the weighted Hessian's derivative
// along v the weighted third derivative (chain-local coordinates, the rest of q held).
TEST_P(SphereDerivativesOnRobots, MatchCentralDifferences) {
  const KinematicModel model = robot(GetParam());
  const int nq = model.numCoordinates();
  std::mt19937 random(11);
  double second = 0.0, weighted = 0.0, third = 0.0;
  for (int trial = 0; trial < 3; ++trial) {
    const Eigen::VectorXd q = fesd_test::randomVector(nq, random);
    const Eigen::Vector3d w = fesd_test::randomVector(3, random);
    for (int s = 0; s < static_cast<int>(model.spheres.size()); ++s) {
      const std::vector<int>& chain = model.chainOf(s);
      const int n = static_cast<int>(chain.size());
      if (n == 0) continue;
      const Eigen::VectorXd v = fesd_test::randomVector(n, random);
      // The derivatives at q with the chain's coordinates replaced by `local`.
      const auto at = [&](const Eigen::VectorXd& local) {
        Eigen::VectorXd moved = q;
        for (int a = 0; a < n; ++a) moved(chain[a]) = local(a);
        fesd::KinematicData data;
        fesd::forwardKinematics(model, moved, data);
        fesd::SphereDerivatives derivatives;
        derivatives.compute(model, data, s);
        return derivatives;
      };
      Eigen::VectorXd local(n);
      for (int a = 0; a < n; ++a) local(a) = q(chain[a]);
      const fesd::SphereDerivatives exact = at(local);
      for (int b = 0; b < n; ++b) {
        const auto column = [&](const Eigen::VectorXd& l) -> Eigen::VectorXd {
          return at(l).jacobian().col(b);
        };
        const Eigen::MatrixXd column_derivative =
            fesd_test::finiteDifferenceJacobian(column, local);
        for (int a = 0; a < n; ++a) {
          second = std::max(second,
                            (exact.second(a, b) - column_derivative.col(a)).cwiseAbs().maxCoeff());
        }
      }
      const auto weighted_gradient = [&](const Eigen::VectorXd& l) -> Eigen::VectorXd {
        return at(l).jacobian().transpose() * w;
      };
      const auto hessian_along_v = [&](const Eigen::VectorXd& l) -> Eigen::VectorXd {
        Eigen::MatrixXd hessian;
        at(l).weightedHessian(w, hessian);
        return hessian * v;
      };
      Eigen::MatrixXd hessian, third_derivative;
      exact.weightedHessian(w, hessian);
      exact.weightedThirdDerivative(w, v, third_derivative);
      weighted = std::max(weighted,
                          (hessian - fesd_test::finiteDifferenceJacobian(weighted_gradient, local))
                              .cwiseAbs()
                              .maxCoeff());
      // Column k of the difference quotient of H[w] v is T[w, e_k] v = T[w, v] e_k.
      third = std::max(
          third, (third_derivative - fesd_test::finiteDifferenceJacobian(hessian_along_v, local))
                     .cwiseAbs()
                     .maxCoeff());
    }
  }
  EXPECT_LT(second, fesd_test::kTolerance);
  EXPECT_LT(weighted, fesd_test::kTolerance);
  EXPECT_LT(third, fesd_test::kTolerance);
}

INSTANTIATE_TEST_SUITE_P(Kinematics, SphereDerivativesOnRobots,
                         ::testing::Values("planar_arm.urdf", "panda_spherized.urdf", "mixed",
                                           "panda_spherized.urdf@0.5", "mixed@3"));

}  // namespace
