// Every model and constraint derivative against central finite differences at random points:
// the analytic and AD model functions, and the assembled NLP (Jacobian and Lagrangian Hessian).
#include <cmath>
#include <random>

#include <gtest/gtest.h>

#include "fesd_trajopt/discretization/pds_discretization.h"
#include "fesd_trajopt/examples/circle_example.h"
#include "fesd_trajopt/function/affine_function.h"
#include "fesd_trajopt/function/quadratic_function.h"
#include "fesd_trajopt/model/autodiff_model.h"
#include "fesd_trajopt/scene/disc_scene.h"
#include "finite_differences.h"

namespace {

using fesd_test::checkAgainstFiniteDifferences;
using fesd_test::randomVector;

constexpr double kTolerance = 1e-6;

/// A nonlinear DCS whose constraint has nonzero third derivatives, so the velocity's Hessian
/// (which contains them) is exercised: x in R^3, u in R^2, two constraints.
struct BeadDynamics {
  template <class T>
  void operator()(const T* x, const T* u, T* f) const {
    using std::cos;
    using std::exp;
    using std::sin;
    f[0] = u[0] * cos(x[2]) + x[1] * x[0] * x[0];
    f[1] = sin(x[0]) * u[1];
    f[2] = x[0] * x[1] - exp(0.1 * x[2]) + u[0] * u[1];
  }
};
struct BeadConstraints {
  template <class T>
  void operator()(const T* x, T* c) const {
    using std::exp;
    using std::sin;
    c[0] = 1.0 - x[0] * x[0] - x[1] * x[1] - 0.5 * sin(x[2]) * sin(x[2]);
    c[1] = exp(0.2 * x[0]) * x[1] + 0.3 * x[2] * x[2] * x[2];
  }
};

std::shared_ptr<const fesd::DcsModel> beadModel() {
  return std::make_shared<fesd::DcsModel>(
      fesd::makeAutoDiffModel(3, 2, 2, BeadDynamics{}, BeadConstraints{}, "bead"));
}

TEST(ModelDerivatives, AutoDiffModelAgainstFiniteDifferences) {
  std::mt19937 random(7);
  const auto model = beadModel();
  for (int trial = 0; trial < 20; ++trial) {
    const Eigen::VectorXd z = randomVector(7, random);  // (x, u, lambda)
    const auto velocity =
        checkAgainstFiniteDifferences(*model->velocity(), z, randomVector(3, random));
    EXPECT_LT(velocity.jacobian, kTolerance);
    EXPECT_LT(velocity.hessian, kTolerance);
    const auto constraints =
        checkAgainstFiniteDifferences(*model->constraints(), z.head(3), randomVector(2, random));
    EXPECT_LT(constraints.jacobian, kTolerance);
    EXPECT_LT(constraints.hessian, kTolerance);
  }
}

TEST(ModelDerivatives, AutoDiffVelocityIsDynamicsPlusConstraintGradientTimesLambda) {
  std::mt19937 random(3);
  const auto model = beadModel();
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd z = randomVector(7, random);
    Eigen::VectorXd v(3), f(3);
    model->velocity()->evaluate(z.data(), v.data());
    BeadDynamics{}(z.data(), z.data() + 3, f.data());
    const Eigen::MatrixXd constraint_jacobian = fesd_test::finiteDifferenceJacobian(
        [](const Eigen::VectorXd& x) {
          Eigen::VectorXd c(2);
          BeadConstraints{}(x.data(), c.data());
          return c;
        },
        z.head(3));
    EXPECT_LT((v - f - constraint_jacobian.transpose() * z.tail(2)).norm(), 1e-8);
  }
}

TEST(ModelDerivatives, AnalyticCircleExampleMatchesFiniteDifferencesAndAutoDiff) {
  std::mt19937 random(11);
  const auto analytic = fesd::circle_example::model();
  const auto autodiff = fesd::circle_example::autodiffModel();
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd z = randomVector(3, random, -3.0, 3.0);
    const auto errors =
        checkAgainstFiniteDifferences(*analytic->velocity(), z, randomVector(2, random));
    EXPECT_LT(errors.jacobian, kTolerance);
    EXPECT_LT(errors.hessian, kTolerance);
    const auto c_errors =
        checkAgainstFiniteDifferences(*analytic->constraints(), z.head(2), randomVector(1, random));
    EXPECT_LT(c_errors.jacobian, kTolerance);
    EXPECT_LT(c_errors.hessian, kTolerance);
    EXPECT_LT((fesd_test::exactJacobian(*analytic->velocity(), z) -
               fesd_test::exactJacobian(*autodiff->velocity(), z))
                  .norm(),
              1e-14);
  }
}

TEST(ModelDerivatives, QuadraticAndAffineFunctions) {
  std::mt19937 random(5);
  Eigen::SparseMatrix<double> q(3, 3);
  q.insert(0, 0) = 2.0;
  q.insert(1, 2) = -0.5;
  q.insert(2, 1) = -0.5;
  q.insert(2, 2) = 1.0;
  const fesd::QuadraticFunction quadratic(q, Eigen::Vector3d(0.0, 1.0, -2.0), 3.0);
  Eigen::SparseMatrix<double> a(2, 3);
  a.insert(0, 1) = 4.0;
  a.insert(1, 0) = -1.0;
  a.insert(1, 2) = 0.5;
  const fesd::AffineFunction affine(a, Eigen::Vector2d(1.0, -1.0));
  for (int trial = 0; trial < 10; ++trial) {
    const Eigen::VectorXd z = randomVector(3, random, -2.0, 2.0);
    const auto qe = checkAgainstFiniteDifferences(quadratic, z, randomVector(1, random));
    EXPECT_LT(qe.jacobian, kTolerance);
    EXPECT_LT(qe.hessian, kTolerance);
    const auto ae = checkAgainstFiniteDifferences(affine, z, randomVector(2, random));
    EXPECT_LT(ae.jacobian, kTolerance);
    EXPECT_LT(ae.hessian, kTolerance);
  }
  const auto distance = fesd::QuadraticFunction::weightedDistance(Eigen::Vector2d(2.0, 0.5),
                                                                  Eigen::Vector2d(1.0, -1.0));
  double value;
  const Eigen::Vector2d at(3.0, 1.0);
  distance->evaluate(at.data(), &value);
  EXPECT_DOUBLE_EQ(value, 2.0 * 4.0 + 0.5 * 4.0);
}

/// A scene with every kind of contact pair: bodies (actuated and passive), an obstacle, walls.
fesd::DiscScene mixedScene(int dimension, std::mt19937& random) {
  fesd::DiscScene scene(dimension);
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
  const fesd::DiscScene scene = mixedScene(GetParam(), random);
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

/// A full OCP on the nonlinear model: every kind of NLP piece is present.
fesd::OcpDefinition beadOcp() {
  fesd::OcpDefinition ocp;
  ocp.model = beadModel();
  ocp.initial_state = Eigen::Vector3d(0.3, 0.2, 0.1);
  ocp.horizon = 1.5;
  ocp.num_intervals = 2;
  ocp.control_lower = Eigen::Vector2d(-2.0, -2.0);
  ocp.control_upper = Eigen::Vector2d(2.0, 2.0);
  ocp.lagrange_cost = fesd::makeAutoDiffFunction(5, 1, [](const auto* z, auto* y) {
    using std::sin;
    y[0] = z[0] * z[0] * z[3] * z[3] + sin(z[1]) * z[4];
  });
  ocp.mayer_cost = fesd::makeAutoDiffFunction(3, 1, [](const auto* x, auto* y) {
    using std::exp;
    y[0] = exp(x[0] * x[2]);
  });
  ocp.path_constraints = fesd::makeAutoDiffFunction(5, 2, [](const auto* z, auto* g) {
    g[0] = z[0] + z[3] * z[3];
    g[1] = z[1] * z[4] - 1.0;
  });
  ocp.terminal_constraints = fesd::makeAutoDiffFunction(
      3, 1, [](const auto* x, auto* g) { g[0] = x[0] * x[0] + x[2] - 2.0; });
  return ocp;
}

struct NlpCase {
  bool switch_detection;
  fesd::CrossComplementarity cross;
  int stages;
  fesd::PdsStepEquilibration equilibration = fesd::PdsStepEquilibration::kPolishing;
};

class NlpDerivatives : public ::testing::TestWithParam<NlpCase> {};

TEST_P(NlpDerivatives, JacobianAndLagrangianHessianAgainstFiniteDifferences) {
  fesd::DiscretizationOptions options;
  options.num_stages = GetParam().stages;
  options.num_elements = 3;
  options.switch_detection = GetParam().switch_detection;
  options.cross_complementarity = GetParam().cross;
  options.pds.step_equilibration = GetParam().equilibration;
  fesd::PdsDiscretization discretization(beadOcp(), options);
  const auto errors = fesd_test::checkRelaxedNlpAtRandomPoints(discretization.nlp(), 3, 17);
  EXPECT_LT(errors.jacobian, kTolerance);
  EXPECT_LT(errors.hessian, kTolerance);
}

INSTANTIATE_TEST_SUITE_P(
    Formulations, NlpDerivatives,
    ::testing::Values(NlpCase{true, fesd::CrossComplementarity::kElementSums, 2},
                      NlpCase{true, fesd::CrossComplementarity::kStagePairs, 2},
                      NlpCase{true, fesd::CrossComplementarity::kElementSums, 3},
                      NlpCase{true, fesd::CrossComplementarity::kElementSums, 2,
                              fesd::PdsStepEquilibration::kBigM},
                      NlpCase{false, fesd::CrossComplementarity::kElementSums, 2}));

TEST(NlpStructure, StandardMethodHasNoCrossComplementarityOrEquilibration) {
  fesd::DiscretizationOptions fesd_options, standard_options;
  fesd_options.num_stages = standard_options.num_stages = 2;
  fesd_options.num_elements = standard_options.num_elements = 3;
  standard_options.switch_detection = false;
  fesd::DiscretizationOptions big_m_options = fesd_options;
  big_m_options.pds.step_equilibration = fesd::PdsStepEquilibration::kBigM;
  fesd::PdsDiscretization with(beadOcp(), fesd_options), without(beadOcp(), standard_options),
      big_m(beadOcp(), big_m_options);
  // Standard: one pair per stage and constraint. FESD: one product of sums per element and
  // constraint; with the paper's big-M equilibration also two max-KKT pairs per inner boundary
  // and constraint, and 8 auxiliaries per boundary and constraint plus one OR per boundary.
  const int elements = 6, stages = 2, constraints = 2, boundaries = 2 * 2;
  EXPECT_EQ(without.nlp().numComplementarities(), elements * stages * constraints);
  EXPECT_EQ(with.nlp().numComplementarities(), elements * constraints);
  EXPECT_EQ(big_m.nlp().numComplementarities(),
            elements * constraints + 2 * boundaries * constraints);
  EXPECT_EQ(big_m.nlp().numVariables() - with.nlp().numVariables(),
            boundaries * (8 * constraints + 1));
  EXPECT_FALSE(without.stepsAreFree());
  EXPECT_TRUE(with.stepsAreFree());
}

}  // namespace
