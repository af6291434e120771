// PdsDiscretization (discretization/pds_discretization.cpp): the NLP's Jacobian and Lagrangian
// Hessian against central finite differences in every formulation, and the NLP's sizes.
#include <cmath>
#include <random>
#include <stdexcept>

#include <gtest/gtest.h>

#include "fesd_trajopt/discretization/pds_discretization.h"
#include "fesd_trajopt/model/autodiff_model.h"
#include "support/bead_model.h"
#include "support/finite_differences.h"

namespace {

using fesd_test::beadModel;
using fesd_test::kTolerance;

constexpr double kForceUpper = 0.3125;

/// A constraint on the bead's (x, u, lambda): forces weighed by the state, and a control.
std::shared_ptr<const fesd::SmoothFunction> beadForces() {
  return fesd::makeAutoDiffFunction(7, 1, [](const auto* z, auto* g) {
    using std::sin;
    g[0] = z[5] * z[0] * z[0] + z[6] * sin(z[1]) + z[3] * z[2];
  });
}

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
  ocp.force_constraints = beadForces();
  ocp.force_upper = Eigen::VectorXd::Constant(1, kForceUpper);
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

TEST(PdsGuesses, ATrajectoryOnTheSameGridIsTakenOverExactly) {
  // A point with free steps, states, multipliers and controls, read as a trajectory and given
  // back: every grid and pair variable comes back (s recomputed from the states, lambda >= 0).
  fesd::DiscretizationOptions options;
  options.num_elements = 3;
  fesd::PdsDiscretization discretization(beadOcp(), options);
  std::vector<double> x = discretization.constantGuess();
  std::mt19937 random(5);
  std::uniform_real_distribution<double> uniform(0.1, 0.9);
  for (int e = 0; e < discretization.numElements(); ++e) {
    x[discretization.stepIndex(e)] *= 0.8 + 0.4 * uniform(random);
    for (int i = 0; i < 2; ++i) {
      for (int d = 0; d < 3; ++d) x[discretization.stateIndex(e, i) + d] = uniform(random);
    }
  }
  for (int k = 0; k < 2; ++k) x[discretization.controlIndex(k)] = uniform(random);
  const fesd::Trajectory trajectory = discretization.extract(x.data());
  fesd::Trajectory with_forces = trajectory;
  for (fesd::ElementValues& element : with_forces.elements) {
    element.stage_multipliers.setConstant(0.25);
    element.stage_multipliers(0, 0) = -1.0;  // clipped to its bound
  }
  const std::vector<double> guess = discretization.guessFromTrajectory(with_forces);
  const fesd::Trajectory back = discretization.extract(guess.data());
  const auto model = std::dynamic_pointer_cast<const fesd::DcsModel>(discretization.ocp().model);
  for (int e = 0; e < discretization.numElements(); ++e) {
    EXPECT_EQ(back.elements[e].step, trajectory.elements[e].step);
    EXPECT_EQ(back.elements[e].stage_states, trajectory.elements[e].stage_states);
    EXPECT_EQ(back.elements[e].stage_multipliers(0, 0), 0.0);
    EXPECT_EQ(back.elements[e].stage_multipliers(0, 1), 0.25);
    for (int i = 0; i < 2; ++i) {
      Eigen::VectorXd c(model->constraintSize());
      model->constraints()->evaluate(back.elements[e].stage_states.col(i).data(), c.data());
      EXPECT_EQ(back.elements[e].stage_constraints.col(i), c.cwiseMax(0.0));
    }
  }
  EXPECT_EQ(back.controls[1], trajectory.controls[1]);
  fesd::Trajectory other_grid = trajectory;
  other_grid.elements.pop_back();
  EXPECT_THROW(discretization.guessFromTrajectory(other_grid), std::invalid_argument);
}

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

TEST(NlpStructure, ForceConstraintsBoundEveryStagePoint) {
  fesd::DiscretizationOptions options;
  options.num_elements = 3;
  fesd::OcpDefinition free = beadOcp();
  free.force_constraints = nullptr;
  free.force_upper.resize(0);
  fesd::PdsDiscretization bounded(beadOcp(), options), unbounded(free, options);
  const fesd::NlpAssembly& nlp = bounded.nlp();
  const int elements = 6, stages = 2;
  ASSERT_EQ(nlp.numConstraints() - unbounded.nlp().numConstraints(), elements * stages);
  std::vector<double> x_lower(nlp.numVariables()), x_upper(nlp.numVariables());
  std::vector<double> g_lower(nlp.numConstraints()), g_upper(nlp.numConstraints());
  nlp.getBounds(x_lower.data(), x_upper.data(), g_lower.data(), g_upper.data());
  std::vector<int> rows;
  for (int r = 0; r < nlp.numConstraints(); ++r) {
    if (g_upper[r] == kForceUpper) rows.push_back(r);
  }
  ASSERT_EQ(static_cast<int>(rows.size()), elements * stages);
  // Their values are g_f at the stage points' states, multipliers and interval's control.
  std::mt19937 random(23);
  const Eigen::VectorXd point = fesd_test::randomVector(nlp.numVariables(), random);
  std::vector<double> g(nlp.numConstraints());
  nlp.constraints(point.data(), g.data());
  const fesd::Trajectory trajectory = bounded.extract(point.data());
  const auto forces = beadForces();
  int row = 0;
  for (int e = 0; e < elements; ++e) {
    const fesd::ElementValues& element = trajectory.elements[e];
    for (int j = 0; j < stages; ++j) {
      Eigen::VectorXd z(7), value(1);
      z << element.stage_states.col(j), trajectory.controls[e / 3],
          element.stage_multipliers.col(j);
      forces->evaluate(z.data(), value.data());
      EXPECT_NEAR(g[rows[row++]], value(0), 1e-12) << e << " " << j;
      EXPECT_EQ(g_lower[rows[row - 1]], -fesd::NlpAssembly::kInfinity);
    }
  }
  fesd::OcpDefinition wrong = beadOcp();
  wrong.force_upper = Eigen::VectorXd::Zero(2);
  EXPECT_THROW(fesd::PdsDiscretization(wrong, options), std::invalid_argument);
}

}  // namespace
