// Step equilibration's residual (step_equilibration_residual.cpp): values and analytic
// derivatives against automatic differentiation of the same formula and against central finite
// differences, for the plain and the tanh-scaled indicator.
#include <gtest/gtest.h>

#include <random>

#include "fesd_trajopt/discretization/step_equilibration_residual.h"
#include "fesd_trajopt/function/autodiff_function.h"
#include "support/finite_differences.h"

namespace {

/// Three modes; five blocks, the third (the common boundary's lambda) in both lambda sums.
fesd::SwitchIndicator threeModeIndicator() {
  return fesd::SwitchIndicator{3, {0, 2}, {2, 1}, {3}, {4, 3}};
}

/// The residual written as in eq. 31, for automatic differentiation.
struct Reference {
  fesd::SwitchIndicator indicator;
  double nominal_step;
  bool tanh_scaled;

  template <class T>
  void operator()(const T* z, T* r) const {
    using std::tanh;
    T eta = indicator(z + 2);
    if (tanh_scaled) eta = tanh(eta);
    r[0] = (z[1] - z[0]) / nominal_step * eta;
  }
};

class StepEquilibrationResidualTest : public ::testing::TestWithParam<bool> {};

TEST_P(StepEquilibrationResidualTest, DerivativesMatchAutomaticDifferentiationAndDifferences) {
  const bool tanh_scaled = GetParam();
  const fesd::StepEquilibrationResidual residual(threeModeIndicator(), 0.3, tanh_scaled);
  ASSERT_EQ(residual.inputSize(), 2 + 5 * 3);
  const auto reference = fesd::makeAutoDiffFunction(
      residual.inputSize(), 1, Reference{threeModeIndicator(), 0.3, tanh_scaled});
  std::mt19937 random(5);
  for (int trial = 0; trial < 5; ++trial) {
    // Steps around the nominal one, blocks nonnegative as in the NLP (scaled so that tanh bends).
    Eigen::VectorXd z = fesd_test::randomVector(residual.inputSize(), random, 0.0, 0.9);
    z(0) += 0.1, z(1) += 0.1;
    const Eigen::VectorXd weights = fesd_test::randomVector(1, random);
    double value, expected;
    residual.evaluate(z.data(), &value);
    reference->evaluate(z.data(), &expected);
    EXPECT_NEAR(value, expected, 1e-13 * std::max(1.0, std::fabs(expected)));
    const Eigen::MatrixXd jacobian = fesd_test::exactJacobian(residual, z);
    const Eigen::MatrixXd hessian = fesd_test::exactHessian(residual, z, weights);
    EXPECT_LT((jacobian - fesd_test::exactJacobian(*reference, z)).cwiseAbs().maxCoeff(), 1e-12);
    EXPECT_LT((hessian - fesd_test::exactHessian(*reference, z, weights)).cwiseAbs().maxCoeff(),
              1e-12);
    EXPECT_GT(hessian.cwiseAbs().maxCoeff(), 1e-3);  // a test that sees the curvature
    const auto errors = fesd_test::checkAgainstFiniteDifferences(residual, z, weights);
    EXPECT_LT(errors.jacobian, fesd_test::kTolerance);
    EXPECT_LT(errors.hessian, fesd_test::kTolerance);
  }
}

INSTANTIATE_TEST_SUITE_P(PlainAndTanh, StepEquilibrationResidualTest, ::testing::Bool());

TEST(StepEquilibrationResidual, StepsEnterOnlyThroughTheirDifference) {
  const fesd::StepEquilibrationResidual residual(threeModeIndicator(), 0.3, false);
  const fesd::SparsityPattern& pattern = residual.hessianPattern();
  for (int k = 0; k < pattern.nonzeros(); ++k) EXPECT_GE(pattern.rows[k], 2);
  // Equal steps: no residual whatever the indicator.
  Eigen::VectorXd z = Eigen::VectorXd::Constant(residual.inputSize(), 0.7);
  double value;
  residual.evaluate(z.data(), &value);
  EXPECT_EQ(value, 0.0);
}

TEST(StepEquilibrationResidual, AnIndicatorSumWithoutBlocksIsRefused) {
  EXPECT_THROW(
      fesd::StepEquilibrationResidual(fesd::SwitchIndicator{2, {0}, {}, {1}, {1}}, 1.0, false),
      std::invalid_argument);
}

}  // namespace
