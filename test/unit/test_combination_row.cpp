// CombinationRow (function/combination_row.cpp): a row of a sparse function at a combination of
// points, its value against the function at the combined point, its derivatives against finite
// differences.
#include <random>

#include <gtest/gtest.h>

#include "fesd_trajopt/function/combination_row.h"
#include "support/finite_differences.h"

namespace {

/// F(x) = (x0^2 - x1, x2 x3 + x2^2) on R^4: each row depends on two coordinates only.
class TwoRows : public fesd::SmoothFunction {
 public:
  TwoRows() {
    for (auto [r, c] : {std::pair{0, 0}, {0, 1}, {1, 2}, {1, 3}}) jacobian_.add(r, c);
    for (auto [r, c] : {std::pair{0, 0}, {2, 2}, {3, 2}}) hessian_.add(r, c);
  }
  int inputSize() const override { return 4; }
  int outputSize() const override { return 2; }
  void evaluate(const double* x, double* y) const override {
    y[0] = x[0] * x[0] - x[1];
    y[1] = x[2] * x[3] + x[2] * x[2];
  }
  const fesd::SparsityPattern& jacobianPattern() const override { return jacobian_; }
  void evaluateJacobian(const double* x, double* v) const override {
    v[0] = 2.0 * x[0];
    v[1] = -1.0;
    v[2] = x[3] + 2.0 * x[2];
    v[3] = x[2];
  }
  const fesd::SparsityPattern& hessianPattern() const override { return hessian_; }
  void evaluateHessian(const double*, const double* w, double* v) const override {
    v[0] = 2.0 * w[0];
    v[1] = 2.0 * w[1];
    v[2] = w[1];
  }

 private:
  fesd::SparsityPattern jacobian_, hessian_;
};

TEST(CombinationRow, IsTheRowAtTheCombinedPointWithExactDerivatives) {
  const auto f = std::make_shared<TwoRows>();
  const std::vector<double> weights{0.3, -0.2, 0.9};
  std::mt19937 random(3);
  for (int row = 0; row < 2; ++row) {
    const fesd::CombinationRow combination(f, row, weights);
    ASSERT_EQ(combination.coordinates(), (std::vector<int>{2 * row, 2 * row + 1}));
    ASSERT_EQ(combination.inputSize(), 6);
    for (int trial = 0; trial < 5; ++trial) {
      const Eigen::VectorXd z = fesd_test::randomVector(6, random, -2.0, 2.0);
      Eigen::Vector4d x = Eigen::Vector4d::Zero();
      for (int b = 0; b < 3; ++b) {
        x(2 * row) += weights[b] * z(2 * b);
        x(2 * row + 1) += weights[b] * z(2 * b + 1);
      }
      Eigen::Vector2d expected;
      f->evaluate(x.data(), expected.data());
      double value;
      combination.evaluate(z.data(), &value);
      EXPECT_NEAR(value, expected(row), 1e-14);
      const auto errors = fesd_test::checkAgainstFiniteDifferences(
          combination, z, fesd_test::randomVector(1, random));
      EXPECT_LT(errors.jacobian, fesd_test::kTolerance);
      EXPECT_LT(errors.hessian, fesd_test::kTolerance);
    }
  }
}

TEST(CombinationRow, RefusesAMissingRowOrNoPoint) {
  const auto f = std::make_shared<TwoRows>();
  EXPECT_THROW(fesd::CombinationRow(f, 2, {1.0}), std::invalid_argument);
  EXPECT_THROW(fesd::CombinationRow(f, 0, {}), std::invalid_argument);
}

}  // namespace

/// y = F(z) through a scratch it keeps: copied for another thread.
class Remembering : public TwoRows {
 public:
  std::shared_ptr<const fesd::SmoothFunction> threadCopy(fesd::ThreadCopies&) const override {
    return std::make_shared<Remembering>();
  }
};

TEST(CombinationRow, ACopyForAnotherThreadCopiesItsFunctionWhereThatKeepsState) {
  const std::vector<double> weights{0.3, -0.2, 0.9};
  const auto shared =
      std::make_shared<fesd::CombinationRow>(std::make_shared<TwoRows>(), 1, weights);
  const auto stateful =
      std::make_shared<fesd::CombinationRow>(std::make_shared<Remembering>(), 1, weights);
  fesd::ThreadCopies copies;
  EXPECT_EQ(copies.function(shared), shared);
  const auto copy = copies.function(stateful);
  ASSERT_NE(copy, stateful);
  const std::vector<double> z{0.5, -1.0, 2.0, 0.3, -0.4, 1.1};
  double original = 0.0, copied = 0.0;
  stateful->evaluate(z.data(), &original);
  copy->evaluate(z.data(), &copied);
  EXPECT_EQ(original, copied);
}
