// Stewart's discretisation (Nurkanovic et al. 2024, Sec. 3; stewart_discretization.cpp): the
// NLP's derivatives against central finite differences, and the structure of its FESD and
// standard discretisations.
#include <stdexcept>

#include <gtest/gtest.h>

#include "fesd_trajopt/discretization/stewart_discretization.h"
#include "fesd_trajopt/examples/filippov_examples.h"
#include "support/finite_differences.h"

namespace {

using fesd_test::kTolerance;

/// OCP (61) on a short grid with an extra path constraint: every kind of NLP piece is present.
fesd::OcpDefinition smallSlidingOcp() {
  fesd::OcpDefinition ocp = fesd::sliding_ocp_example::ocp();
  ocp.num_intervals = 2;
  ocp.horizon = 1.0;
  ocp.path_constraints = fesd::makeAutoDiffFunction(
      6, 1, [](const auto* z, auto* g) { g[0] = z[0] * z[1] + z[4] * z[5] - 3.0; });
  return ocp;
}

struct NlpCase {
  fesd::CollocationFamily family;
  int stages;
  bool switch_detection;
  fesd::CrossComplementarity cross;
  fesd::StepEquilibration equilibration;
};

class StewartNlpDerivatives : public ::testing::TestWithParam<NlpCase> {};

TEST_P(StewartNlpDerivatives, JacobianAndLagrangianHessianAgainstFiniteDifferences) {
  fesd::DiscretizationOptions options;
  options.family = GetParam().family;
  options.num_stages = GetParam().stages;
  options.num_elements = 3;
  options.switch_detection = GetParam().switch_detection;
  options.cross_complementarity = GetParam().cross;
  options.filippov.step_equilibration = GetParam().equilibration;
  fesd::StewartDiscretization discretization(smallSlidingOcp(), options);
  const auto errors = fesd_test::checkRelaxedNlpAtRandomPoints(discretization.nlp(), 2, 17);
  EXPECT_LT(errors.jacobian, kTolerance);
  EXPECT_LT(errors.hessian, kTolerance);
}

using fesd::CollocationFamily;
using fesd::CrossComplementarity;
using fesd::StepEquilibration;
INSTANTIATE_TEST_SUITE_P(
    Formulations, StewartNlpDerivatives,
    ::testing::Values(NlpCase{CollocationFamily::kRadauIIA, 2, true,
                              CrossComplementarity::kElementSums, StepEquilibration::kIndicator},
                      NlpCase{CollocationFamily::kRadauIIA, 1, true,
                              CrossComplementarity::kStagePairs, StepEquilibration::kTanhIndicator},
                      NlpCase{CollocationFamily::kGaussLegendre, 2, true,
                              CrossComplementarity::kElementSums,
                              StepEquilibration::kTanhIndicator},
                      NlpCase{CollocationFamily::kGaussLegendre, 2, false,
                              CrossComplementarity::kElementSums, StepEquilibration::kIndicator}));

TEST(StewartNlpStructure, ComplementarityAndBoundaryPoints) {
  fesd::DiscretizationOptions options;
  options.num_stages = 2;
  options.num_elements = 3;
  const int elements = 6, stages = 2, modes = 4;
  for (auto family : {CollocationFamily::kRadauIIA, CollocationFamily::kGaussLegendre}) {
    options.family = family;
    options.switch_detection = true;
    fesd::StewartDiscretization fesd_method(smallSlidingOcp(), options);
    options.switch_detection = false;
    fesd::StewartDiscretization standard(smallSlidingOcp(), options);
    // Standard: one pair per stage and mode; FESD: one product of sums per element and mode.
    EXPECT_EQ(standard.nlp().numComplementarities(), elements * stages * modes);
    EXPECT_EQ(fesd_method.nlp().numComplementarities(), elements * modes);
    EXPECT_TRUE(fesd_method.stepsAreFree());
    EXPECT_FALSE(standard.stepsAreFree());
    // FESD adds its boundary points (n_f + n_sys each): the start's, and with c_ns != 1 one
    // at every element's end; plus the equilibration's rows (relaxed and equal-steps) per
    // inner boundary and the interval-length rows.
    const int boundary_points = family == CollocationFamily::kRadauIIA ? 1 : elements + 1;
    EXPECT_EQ(fesd_method.nlp().numVariables() - standard.nlp().numVariables(),
              boundary_points * (modes + 2));
    EXPECT_EQ(fesd_method.nlp().numConstraints() - standard.nlp().numConstraints(),
              boundary_points * modes + 2 * 2 * 2 + 2 - (elements * stages - elements) * modes);
  }
}

TEST(StewartNlpStructure, FreeInitialStateIsReleasedWithinItsBounds) {
  fesd::OcpDefinition ocp = fesd::sign_example::ocp(0.5);
  fesd::StewartDiscretization discretization(ocp, fesd::DiscretizationOptions{});
  const int start = discretization.startStateIndex();
  EXPECT_EQ(discretization.nlp().variableLower(start), -3.0);
  EXPECT_EQ(discretization.nlp().variableUpper(start), 3.0);
  discretization.setInitialState(Eigen::VectorXd::Constant(1, 0.25));
  EXPECT_EQ(discretization.nlp().variableLower(start), 0.25);
  EXPECT_EQ(discretization.nlp().variableUpper(start), 0.25);
  discretization.releaseInitialState();
  EXPECT_EQ(discretization.nlp().variableUpper(start), 3.0);
}

TEST(StewartNlpStructure, ForceConstraintsAreRefused) {
  // A Filippov system has no contact forces to bound.
  fesd::OcpDefinition ocp = smallSlidingOcp();
  ocp.force_constraints = ocp.path_constraints;
  EXPECT_THROW(fesd::StewartDiscretization(ocp, fesd::DiscretizationOptions{}),
               std::invalid_argument);
}

}  // namespace
