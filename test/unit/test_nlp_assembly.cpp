// NlpAssembly's active-set tools (nlp/nlp_assembly.cpp): biactiveDescent at a wrongly fixed
// side, active-set polishing (fixActiveSet) when a complementarity side holds fixed data, as
// c and lambda at a simulation step's start point do: such a side cannot be made zero, and
// pairs left biactive (setBiactiveRule); its evaluations on two threads, bit for bit those on
// one.
#include <cmath>
#include <cstring>
#include <memory>
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

namespace {

/// y = (z0 sin z1, z0 z1^2) through a mutable scratch (state between calls, as the kinematics of
/// pair functions): its copies for another thread are counted.
class Stateful : public fesd::SmoothFunction {
 public:
  explicit Stateful(std::shared_ptr<int> copies) : copies_(std::move(copies)) {
    for (int r = 0; r < 2; ++r) {
      for (int c = 0; c < 2; ++c) jacobian_.add(r, c);
    }
    for (auto [r, c] : {std::pair{1, 0}, {1, 1}}) hessian_.add(r, c);
  }
  int inputSize() const override { return 2; }
  int outputSize() const override { return 2; }
  void evaluate(const double* z, double* y) const override {
    remember(z);
    y[0] = z[0] * sine_;
    y[1] = z[0] * z[1] * z[1];
  }
  const fesd::SparsityPattern& jacobianPattern() const override { return jacobian_; }
  void evaluateJacobian(const double* z, double* v) const override {
    remember(z);
    v[0] = sine_;
    v[1] = z[0] * cosine_;
    v[2] = z[1] * z[1];
    v[3] = 2.0 * z[0] * z[1];
  }
  const fesd::SparsityPattern& hessianPattern() const override { return hessian_; }
  void evaluateHessian(const double* z, const double* w, double* v) const override {
    remember(z);
    v[0] = w[0] * cosine_ + w[1] * 2.0 * z[1];
    v[1] = -w[0] * z[0] * sine_ + w[1] * 2.0 * z[0];
  }
  std::shared_ptr<const fesd::SmoothFunction> threadCopy(fesd::ThreadCopies&) const override {
    ++*copies_;
    return std::make_shared<Stateful>(copies_);
  }

 private:
  void remember(const double* z) const {
    sine_ = std::sin(z[1]);
    cosine_ = std::cos(z[1]);
  }
  std::shared_ptr<int> copies_;
  mutable double sine_ = 0.0, cosine_ = 0.0;
  fesd::SparsityPattern jacobian_, hessian_;
};

/// 600 terms of one stateful function on overlapping pairs of 30 variables, half of them scaled
/// by a variable, into 12 rows and the objective: every row and Hessian entry sums many terms.
fesd::NlpAssembly manyTerms(const std::shared_ptr<int>& copies) {
  fesd::NlpAssembly nlp;
  const int first = nlp.addVariables(30, -kInf, kInf);
  const int rows = nlp.addRows(24, 0.0, 0.0);
  const auto function = std::make_shared<Stateful>(copies);
  for (int t = 0; t < 600; ++t) {
    const int a = first + (7 * t) % 30, b = first + (11 * t + 3) % 30;
    const int scale = t % 2 ? first + (t % 5) : -1;
    nlp.addFunctionTerm(function, {a, b == a ? (b + 1) % 30 : b}, scale,
                        {{rows + 2 * (t % 12), 1.0 + 0.1 * (t % 3)}, {rows + 2 * (t % 5), -0.7}});
  }
  nlp.finalize();
  return nlp;
}

}  // namespace

/// The terms evaluated on two threads give the same bits as on one: the additions keep the
/// terms' order, and the helper evaluates copies of a function that keeps state.
TEST(NlpAssembly, TwoThreadsEvaluateToTheSameBitsAsOne) {
  const auto one_copies = std::make_shared<int>(0), two_copies = std::make_shared<int>(0);
  fesd::NlpAssembly one = manyTerms(one_copies), two = manyTerms(two_copies);
  one.setEvaluationThreads(fesd::NlpAssembly::Threads::kOne);
  two.setEvaluationThreads(fesd::NlpAssembly::Threads::kTwo);
  std::vector<double> x(30), y(24);
  for (int i = 0; i < 30; ++i) x[i] = std::sin(1.3 * i) + 0.1 * i;
  for (int r = 0; r < 24; ++r) y[r] = std::cos(0.7 * r);
  const auto bits = [](const std::vector<double>& a, const std::vector<double>& b) {
    return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
  };
  for (int repeat = 0; repeat < 20; ++repeat) {
    std::vector<double> g1(24), g2(24), j1(one.jacobianPattern().nonzeros()), j2(j1.size()),
        h1(one.hessianPattern().nonzeros()), h2(h1.size());
    one.constraints(x.data(), g1.data());
    two.constraints(x.data(), g2.data());
    one.jacobian(x.data(), j1.data());
    two.jacobian(x.data(), j2.data());
    one.hessian(x.data(), 0.5, y.data(), h1.data());
    two.hessian(x.data(), 0.5, y.data(), h2.data());
    ASSERT_TRUE(bits(g1, g2)) << "repeat " << repeat;
    ASSERT_TRUE(bits(j1, j2)) << "repeat " << repeat;
    ASSERT_TRUE(bits(h1, h2)) << "repeat " << repeat;
    x[repeat % 30] += 0.01;
  }
  EXPECT_EQ(*one_copies, 0);
  EXPECT_EQ(*two_copies, 1);  // one copy of the one function, for the helper
}

namespace {

/// A function that fails at every point, as do its copies.
class Failing : public Stateful {
 public:
  Failing() : Stateful(std::make_shared<int>(0)) {}
  void evaluate(const double*, double*) const override { throw std::runtime_error("failed"); }
  std::shared_ptr<const fesd::SmoothFunction> threadCopy(fesd::ThreadCopies&) const override {
    return std::make_shared<Failing>();
  }
};

}  // namespace

/// What a function throws reaches the caller on two threads as on one, whichever thread met it,
/// and the NLP evaluates on after it.
TEST(NlpAssembly, AFunctionsFailureOnTwoThreadsReachesTheCaller) {
  fesd::NlpAssembly nlp;
  const int first = nlp.addVariables(4, -kInf, kInf);
  const int row = nlp.addRows(3, 0.0, 0.0);
  const auto failing = std::make_shared<Failing>();
  const auto fine = std::make_shared<Stateful>(std::make_shared<int>(0));
  for (int t = 0; t < 200; ++t) {
    nlp.addFunctionTerm(t == 150 ? failing : fine, {first + t % 3, first + 3}, -1,
                        {{row, 1.0}, {row + 1, 1.0}});
  }
  nlp.finalize();
  nlp.setEvaluationThreads(fesd::NlpAssembly::Threads::kTwo);
  const std::vector<double> x{0.1, 0.2, 0.3, 0.4};
  std::vector<double> g(3);
  for (int repeat = 0; repeat < 50; ++repeat) {
    EXPECT_THROW(nlp.constraints(x.data(), g.data()), std::runtime_error);
  }
  std::vector<double> jacobian(nlp.jacobianPattern().nonzeros());
  nlp.jacobian(x.data(), jacobian.data());  // Failing's Jacobian is Stateful's
  EXPECT_TRUE(std::isfinite(jacobian[0]));
}

TEST(NlpAssembly, AFunctionTermsRowsMustLieInTheNlp) {
  fesd::NlpAssembly nlp;
  const int first = nlp.addVariables(2, -kInf, kInf);
  const int row = nlp.addRows(1, 0.0, 0.0);
  nlp.addFunctionTerm(std::make_shared<Stateful>(std::make_shared<int>(0)), {first, first + 1}, -1,
                      {{row, 1.0}});  // two outputs into one row
  EXPECT_THROW(nlp.finalize(), std::invalid_argument);
}
