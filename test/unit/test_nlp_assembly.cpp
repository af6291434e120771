// NlpAssembly's active-set tools (nlp/nlp_assembly.cpp): biactiveDescent at a wrongly fixed
// side, active-set polishing (fixActiveSet) when a complementarity side holds fixed data, as
// c and lambda at a simulation step's start point do: such a side cannot be made zero, and
// pairs left biactive (setBiactiveRule).
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/function/quadratic_function.h"
#include "fesd_trajopt/nlp/nlp_assembly.h"

namespace {

/// min (x - 1)^2 + (y + 1)^2  s.t.  0 <= x _|_ y >= 0: the minimiser is (1, 0). Fixing the wrong
/// side, x = 0, leaves y = 0 as well: a biactive point where raising x descends along
/// -df/dx = 2, which is |grad f|_inf there.
TEST(NlpAssembly, BiactiveDescentDetectsTheWrongFixedSide) {
  fesd::NlpAssembly nlp;
  const int x = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
  const int y = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
  nlp.addFunctionTerm(fesd::QuadraticFunction::weightedDistance(Eigen::Vector2d::Ones(),
                                                                Eigen::Vector2d(1.0, -1.0)),
                      {x, y}, -1, {{fesd::NlpAssembly::kObjective, 1.0}});
  nlp.addComplementarity({{x, 1.0}}, {{y, 1.0}});
  nlp.finalize();
  const std::vector<double> origin{0.0, 0.0}, no_multipliers(nlp.numConstraints(), 0.0);
  const std::vector<double> x_smaller{1e-3, 1e-2}, y_smaller{1e-2, 1e-3};
  ASSERT_TRUE(nlp.fixActiveSet(x_smaller.data()));
  EXPECT_DOUBLE_EQ(nlp.biactiveDescent(origin.data(), no_multipliers.data()), 1.0);
  nlp.releaseActiveSet();
  ASSERT_TRUE(nlp.fixActiveSet(y_smaller.data()));
  const std::vector<double> minimiser{1.0, 0.0};
  EXPECT_DOUBLE_EQ(nlp.biactiveDescent(minimiser.data(), no_multipliers.data()), 0.0);
  nlp.releaseActiveSet();
  EXPECT_THROW(nlp.biactiveDescent(minimiser.data(), no_multipliers.data()), std::logic_error);
}

TEST(NlpAssembly, FixedPairsNameEachPairsZeroSideAndTheBoundsBeforeTheActiveSet) {
  fesd::NlpAssembly nlp;
  const int x = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
  const int y = nlp.addVariables(1, 0.0, 5.0);
  const int u = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
  const int v = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
  nlp.addComplementarity({{x, 1.0}}, {{y, 2.0}});
  nlp.addComplementarity({{u, 1.0}}, {{v, 1.0}});
  nlp.finalize();
  EXPECT_THROW(nlp.fixedPairs(), std::logic_error);
  const std::vector<double> point{1.0, 0.0, 0.0, 3.0};
  ASSERT_TRUE(nlp.fixGivenActiveSet({false, true}, point.data()));
  const std::vector<fesd::FixedPair> pairs = nlp.fixedPairs();
  ASSERT_EQ(pairs.size(), 2u);
  EXPECT_FALSE(pairs[0].zero_side_is_left);  // y is fixed: the right side
  EXPECT_EQ(pairs[0].zero_side[0].variable, y);
  EXPECT_EQ(pairs[0].zero_side[0].coefficient, 2.0);
  EXPECT_EQ(pairs[0].other_side[0].variable, x);
  EXPECT_TRUE(pairs[1].zero_side_is_left);
  EXPECT_EQ(pairs[1].zero_side[0].variable, u);
  EXPECT_FALSE(pairs[0].biactive || pairs[1].biactive);
  std::vector<double> lower(4), upper(4);
  nlp.boundsBeforeActiveSet(lower.data(), upper.data());
  EXPECT_EQ(upper[y], 5.0);  // fixed to 0 now, 5 in the MPCC
  EXPECT_EQ(nlp.variableUpper(y), 0.0);
  EXPECT_EQ(upper[u], fesd::NlpAssembly::kInfinity);
  EXPECT_EQ(nlp.variableUpper(u), 0.0);
  nlp.releaseActiveSet();
  EXPECT_THROW(nlp.boundsBeforeActiveSet(lower.data(), upper.data()), std::logic_error);
}

constexpr double kInf = fesd::NlpAssembly::kInfinity;

/// (d + a) _|_ b with d fixed data, a and b free and nonnegative; no objective needed.
struct PairWithData {
  fesd::NlpAssembly nlp;
  int data, a, b;
  explicit PairWithData(double data_value) {
    data = nlp.addVariables(1, data_value, data_value, data_value);
    a = nlp.addVariables(1, 0.0, kInf);
    b = nlp.addVariables(1, 0.0, kInf);
    nlp.addComplementarity({{data, 1.0}, {a, 1.0}}, {{b, 1.0}});
    nlp.finalize();
  }
};

TEST(PolishingWithData, TheSideWithNonzeroDataStaysFreeEvenWhenSmaller) {
  PairWithData pair(0.5);
  const double x[] = {0.5, 0.0, 0.7};  // left 0.5 < right 0.7
  ASSERT_TRUE(pair.nlp.fixActiveSet(x));
  EXPECT_EQ(pair.nlp.variableUpper(pair.b), 0.0);   // the right side is the zero side
  EXPECT_EQ(pair.nlp.variableUpper(pair.a), kInf);  // the left side stays free
  pair.nlp.releaseActiveSet();
  EXPECT_EQ(pair.nlp.variableUpper(pair.b), kInf);
}

TEST(PolishingWithData, NegligibleDataCountsAsZero) {
  PairWithData pair(1e-12);  // e.g. c(x) of a start point on a curved boundary
  const double x[] = {1e-12, 0.0, 0.7};
  ASSERT_TRUE(pair.nlp.fixActiveSet(x));
  EXPECT_EQ(pair.nlp.variableUpper(pair.a), 0.0);
  EXPECT_EQ(pair.nlp.variableUpper(pair.b), kInf);
}

TEST(PolishingWithData, TheUnknownsResidualLeavesOutOnlyNegligibleData) {
  PairWithData negligible(-9e-10);  // a start 9e-10 inside the boundary
  const double x[] = {-9e-10, 0.0, 5.0};
  EXPECT_NEAR(negligible.nlp.complementarityResidual(x), 4.5e-9, 1e-20);
  EXPECT_EQ(negligible.nlp.complementarityResidualOfUnknowns(x), 0.0);
  PairWithData data(2e-9);  // beyond kNegligibleFixedValue: it counts
  const double y[] = {2e-9, 0.0, 5.0};
  EXPECT_NEAR(data.nlp.complementarityResidualOfUnknowns(y), 1e-8, 1e-20);
  const double z[] = {-9e-10, 1e-3, 5.0};  // an unknown side's value always counts
  EXPECT_NEAR(negligible.nlp.complementarityResidualOfUnknowns(z), 5e-3, 1e-15);
}

TEST(PolishingWithData, RefusedWhenBothSidesHoldNonzeroData) {
  fesd::NlpAssembly nlp;
  const int c0 = nlp.addVariables(1, 0.2, 0.2, 0.2);
  const int lambda0 = nlp.addVariables(1, 0.3, 0.3, 0.3);
  const int a = nlp.addVariables(1, 0.0, kInf);
  nlp.addComplementarity({{c0, 1.0}, {a, 1.0}}, {{lambda0, 1.0}});
  nlp.finalize();
  const double x[] = {0.2, 0.3, 0.0};
  EXPECT_FALSE(nlp.fixActiveSet(x));
  EXPECT_EQ(nlp.variableUpper(a), kInf);  // nothing changed
}

/// x _|_ y at sigma = 1e-2: the relaxation's scale is sqrt(sigma) = 0.1, so with the fraction 0.1
/// a pair whose sides are both at most 0.01 is biactive and keeps both sides free.
TEST(PolishingBiactivePairs, BothSidesFarBelowTheRelaxationStayFree) {
  fesd::NlpAssembly nlp;
  const int x = nlp.addVariables(1, 0.0, kInf);
  const int y = nlp.addVariables(1, 0.0, kInf);
  const int row = nlp.addComplementarity({{x, 1.0}}, {{y, 1.0}});
  nlp.finalize();
  nlp.setRelaxation(1e-2);
  nlp.setBiactiveRule(0.1, 1e-2);
  std::vector<double> g_lower(1), g_upper(1), x_lower(2), x_upper(2);
  const double biactive[] = {2e-3, 5e-3};
  ASSERT_TRUE(nlp.fixActiveSet(biactive));
  EXPECT_EQ(nlp.variableUpper(x), kInf);
  EXPECT_EQ(nlp.variableUpper(y), kInf);
  nlp.getBounds(x_lower.data(), x_upper.data(), g_lower.data(), g_upper.data());
  EXPECT_EQ(g_upper[row], kInf);         // the product row is dropped: the relaxed NLP of the pair
  EXPECT_TRUE(nlp.fixedAtAboutZero(x));  // zero in the active set's meaning (step equilibration)
  EXPECT_TRUE(nlp.fixedAtAboutZero(y));
  const std::vector<double> no_multipliers(nlp.numConstraints(), 0.0);
  EXPECT_EQ(nlp.biactiveDescent(biactive, no_multipliers.data()), 0.0);  // Ipopt's signs hold
  EXPECT_TRUE(nlp.flipBiactivePairs(biactive).empty());
  nlp.releaseActiveSet();
  EXPECT_FALSE(nlp.fixedAtAboutZero(x));
  EXPECT_EQ(nlp.identifyActiveSet(biactive), std::vector<bool>{false});
  // One side at the relaxation's scale: complementary, its smaller side fixed as before.
  const double complementary[] = {2e-3, 0.05};
  ASSERT_TRUE(nlp.fixActiveSet(complementary));
  EXPECT_EQ(nlp.variableUpper(x), 0.0);
  EXPECT_EQ(nlp.variableUpper(y), kInf);
  nlp.releaseActiveSet();
  // Without the rule every pair gets a fixed side.
  nlp.setBiactiveRule(0.0, 1e-2);
  ASSERT_TRUE(nlp.fixActiveSet(biactive));
  EXPECT_EQ(nlp.variableUpper(x), 0.0);
}

}  // namespace

/// Rows x + y = 3 (equality), x - y in [0, 1] (inequality): only the equality's residual counts.
TEST(NlpAssembly, EqualityResidualMeasuresOnlyTheEqualityRows) {
  fesd::NlpAssembly nlp;
  const int x = nlp.addVariables(1, -kInf, kInf);
  const int y = nlp.addVariables(1, -kInf, kInf);
  const int sum = nlp.addRows(1, 3.0, 3.0);
  nlp.addLinear(sum, {{x, 1.0}, {y, 1.0}});
  const int difference = nlp.addRows(1, 0.0, 1.0);
  nlp.addLinear(difference, {{x, 1.0}, {y, -1.0}});
  nlp.finalize();
  const double feasible[] = {2.0, 1.0}, off[] = {5.0, -0.5}, below[] = {1.0, 1.5};
  EXPECT_DOUBLE_EQ(nlp.equalityResidual(feasible), 0.0);
  EXPECT_DOUBLE_EQ(nlp.equalityResidual(off), 1.5);    // x - y = 5.5 violates only the range
  EXPECT_DOUBLE_EQ(nlp.equalityResidual(below), 0.5);  // 2.5 against 3
}

namespace {

/// The row h * F(z) with F(z) = z0^2 + z1^2 (an element length times a stage function).
fesd::NlpAssembly scaledRow() {
  fesd::NlpAssembly nlp;
  const int z = nlp.addVariables(2, -kInf, kInf);
  const int h = nlp.addVariables(1, 0.0, kInf);
  const int row = nlp.addRows(1, 0.0, 0.0);
  nlp.addFunctionTerm(
      fesd::QuadraticFunction::weightedDistance(Eigen::Vector2d::Ones(), Eigen::Vector2d::Zero()),
      {z, z + 1}, h, {{row, 1.0}});
  nlp.finalize();
  return nlp;
}

Eigen::MatrixXd dense(const fesd::SparsityPattern& pattern, const std::vector<double>& values,
                      int rows, int cols) {
  Eigen::MatrixXd matrix = Eigen::MatrixXd::Zero(rows, cols);
  for (int e = 0; e < pattern.nonzeros(); ++e)
    matrix(pattern.rows[e], pattern.cols[e]) += values[e];
  return matrix;
}

}  // namespace

/// A term scaled by a variable (h F(z)): its Jacobian and Hessian against the analytic ones,
/// whatever point the evaluation before was at (the function objects keep state between calls).
TEST(NlpAssembly, AScaledTermsDerivativesAreThoseOfTheirOwnPoint) {
  fesd::NlpAssembly nlp = scaledRow();
  const std::vector<double> x1{1.0, 2.0, 0.5}, x2{3.0, -1.0, 2.0}, y{1.5};
  std::vector<double> g(1), jacobian(nlp.jacobianPattern().nonzeros()),
      hessian(nlp.hessianPattern().nonzeros());
  // At x2: d/dz = 2 h z = (12, -4), d/dh = |z|^2 = 10; y Hess: 2 y h I on z, 2 y z on (h, z).
  Eigen::MatrixXd expected_jacobian(1, 3);
  expected_jacobian << 12.0, -4.0, 10.0;
  Eigen::MatrixXd expected_hessian = Eigen::MatrixXd::Zero(3, 3);
  expected_hessian(0, 0) = expected_hessian(1, 1) = 2.0 * 1.5 * 2.0;
  expected_hessian(2, 0) = expected_hessian(0, 2) = 2.0 * 1.5 * 3.0;
  expected_hessian(2, 1) = expected_hessian(1, 2) = 2.0 * 1.5 * -1.0;
  for (bool same_point : {false, true}) {
    nlp.constraints(same_point ? x2.data() : x1.data(), g.data());
    nlp.jacobian(x2.data(), jacobian.data());
    EXPECT_TRUE(dense(nlp.jacobianPattern(), jacobian, 1, 3).isApprox(expected_jacobian))
        << dense(nlp.jacobianPattern(), jacobian, 1, 3);
    if (!same_point) nlp.jacobian(x1.data(), jacobian.data());
    nlp.hessian(x2.data(), 0.0, y.data(), hessian.data());
    Eigen::MatrixXd triangle = dense(nlp.hessianPattern(), hessian, 3, 3);
    Eigen::MatrixXd symmetric = triangle + triangle.transpose();
    symmetric.diagonal() = triangle.diagonal();
    EXPECT_TRUE(symmetric.isApprox(expected_hessian)) << symmetric;
  }
}
