// The multifrontal LDL^T with threshold pivoting (linalg/multifrontal_ldlt.cpp): solutions and
// inertia against dense references on random KKT matrices, delayed and 2x2 pivots, singular and
// non-finite matrices, refinement, repeated factorisations of one pattern.
#include <cmath>
#include <memory>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "fesd_trajopt/linalg/multifrontal_ldlt.h"
#include "support/sparse_matrices.h"

namespace {

using fesd::linalg::FactorReport;
using fesd::linalg::FillOrdering;
using fesd::linalg::MultifrontalLdlt;
using fesd::linalg::PivotSettings;
using fesd::linalg::SupernodalAnalysis;
using fesd_test::LowerMatrix;

int negativeEigenvalues(const Eigen::MatrixXd& dense) {
  const Eigen::VectorXd eigenvalues =
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(dense).eigenvalues();
  return static_cast<int>((eigenvalues.array() < 0.0).count());
}

struct Solved {
  FactorReport report;
  double error;  ///< |x - x_dense|_inf / |x_dense|_inf
};

Solved factorAndSolve(const Eigen::MatrixXd& dense, FillOrdering ordering,
                      const PivotSettings& settings = {}) {
  const LowerMatrix matrix = fesd_test::lowerMatrix(dense);
  auto analysis = std::make_shared<const SupernodalAnalysis>(matrix.pattern, ordering);
  MultifrontalLdlt ldlt(analysis);
  Solved solved;
  solved.report = ldlt.factor(matrix.values.data(), settings);
  if (!solved.report.usable()) return solved;
  const Eigen::VectorXd expected = Eigen::VectorXd::LinSpaced(dense.rows(), -1.0, 2.0);
  Eigen::VectorXd x = dense * expected;
  ldlt.solve(x.data());
  solved.error = (x - expected).lpNorm<Eigen::Infinity>() / expected.lpNorm<Eigen::Infinity>();
  return solved;
}

TEST(MultifrontalLdlt, SolvesRandomKktMatricesWithTheirInertia) {
  PivotSettings settings;
  settings.threshold = 0.01;  // Ipopt's 1e-8 trades accuracy for sparsity; it refines
  for (uint32_t seed = 0; seed < 12; ++seed) {
    for (const bool convex : {true, false}) {
      for (const FillOrdering ordering : {FillOrdering::kAmd, FillOrdering::kMetis}) {
        const Eigen::MatrixXd kkt = fesd_test::randomKkt(60, 25, 0.06, convex, 0.0, seed);
        const Solved solved = factorAndSolve(kkt, ordering, settings);
        ASSERT_TRUE(solved.report.usable()) << "seed " << seed;
        EXPECT_LT(solved.error, 1e-9) << "seed " << seed;
        EXPECT_EQ(solved.report.negative, negativeEigenvalues(kkt)) << "seed " << seed;
      }
    }
  }
}

TEST(MultifrontalLdlt, ZeroDiagonalsNeedTwoByTwoPivotsOrDelays) {
  // A KKT matrix with a zero constraint block: every constraint column has a zero pivot where
  // it comes first, so some columns must pair up or wait for their partners.
  int two_by_two = 0, delayed = 0;
  for (uint32_t seed = 0; seed < 8; ++seed) {
    const Eigen::MatrixXd kkt = fesd_test::randomKkt(40, 30, 0.05, false, 0.0, seed);
    const Solved solved = factorAndSolve(kkt, FillOrdering::kAmd);
    ASSERT_TRUE(solved.report.usable());
    EXPECT_LT(solved.error, 1e-9);
    EXPECT_EQ(solved.report.negative, negativeEigenvalues(kkt));
    two_by_two += solved.report.two_by_two;
    delayed += solved.report.delayed;
  }
  EXPECT_GT(two_by_two, 0);
  EXPECT_GT(delayed, 0);
}

TEST(MultifrontalLdlt, LargeFrontsUseThePanelledUpdate) {
  // Dense enough that fronts exceed the dense-update size (64 rows) and several panels.
  const Eigen::MatrixXd kkt = fesd_test::randomKkt(160, 60, 0.3, false, 0.0, 3);
  const Solved solved = factorAndSolve(kkt, FillOrdering::kAmd);
  ASSERT_TRUE(solved.report.usable());
  EXPECT_LT(solved.error, 1e-8);
  EXPECT_EQ(solved.report.negative, negativeEigenvalues(kkt));
}

TEST(MultifrontalLdlt, StricterThresholdsGiveTheSameSolution) {
  const Eigen::MatrixXd kkt = fesd_test::randomKkt(50, 20, 0.08, false, 0.0, 5);
  for (const double threshold : {0.0, 1e-8, 1e-4, 0.1, 0.5}) {
    PivotSettings settings;
    settings.threshold = threshold;
    const Solved solved = factorAndSolve(kkt, FillOrdering::kAmd, settings);
    ASSERT_TRUE(solved.report.usable()) << threshold;
    EXPECT_LT(solved.error, 1e-9) << threshold;
    EXPECT_EQ(solved.report.negative, negativeEigenvalues(kkt)) << threshold;
  }
}

TEST(MultifrontalLdlt, SingularMatricesAreReported) {
  // [2I J^T; J 0] with two equal constraint rows: rank deficient by one, and in exact binary
  // arithmetic the last pivot is exactly zero whatever the order.
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(9, 9);
  kkt.topLeftCorner(6, 6) = 2.0 * Eigen::MatrixXd::Identity(6, 6);
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(3, 6);
  jacobian << 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0;
  kkt.bottomLeftCorner(3, 6) = jacobian;
  kkt.topRightCorner(6, 3) = jacobian.transpose();
  for (const FillOrdering ordering : {FillOrdering::kAmd, FillOrdering::kMetis}) {
    const Solved solved = factorAndSolve(kkt, ordering);
    EXPECT_TRUE(solved.report.finite);
    EXPECT_EQ(solved.report.zero, 1);
    EXPECT_FALSE(solved.report.usable());
  }
}

TEST(MultifrontalLdlt, NonFiniteValuesAreReported) {
  Eigen::MatrixXd kkt = fesd_test::randomKkt(20, 5, 0.1, true, 0.0, 8);
  kkt(3, 3) = std::nan("");
  EXPECT_FALSE(factorAndSolve(kkt, FillOrdering::kAmd).report.finite);
}

TEST(MultifrontalLdlt, RefinementReachesTheTolerance) {
  // Badly scaled: entries from 1e-8 to 1e8, as in late interior-point iterations.
  Eigen::MatrixXd kkt = fesd_test::randomKkt(50, 20, 0.08, true, 0.0, 9);
  for (int i = 0; i < kkt.rows(); ++i) {
    if (kkt(i, i) > 0.0) kkt(i, i) *= (i % 3 == 0) ? 1e8 : 1.0;
  }
  const LowerMatrix matrix = fesd_test::lowerMatrix(kkt);
  MultifrontalLdlt ldlt(
      std::make_shared<const SupernodalAnalysis>(matrix.pattern, FillOrdering::kAmd));
  ASSERT_TRUE(ldlt.factor(matrix.values.data(), PivotSettings{}).usable());
  Eigen::VectorXd x = kkt * Eigen::VectorXd::Ones(kkt.rows());
  const fesd::linalg::SolveReport report = ldlt.solveRefined(x.data(), 1e-15, 5);
  EXPECT_LE(report.residual, 1e-15);
  EXPECT_LT((x - Eigen::VectorXd::Ones(kkt.rows())).lpNorm<Eigen::Infinity>(), 1e-8);
}

TEST(MultifrontalLdlt, RefactorisingOnePatternGivesEachMatrixItsSolution) {
  const Eigen::MatrixXd first = fesd_test::randomKkt(40, 15, 0.1, false, 0.0, 10);
  Eigen::MatrixXd second = first;
  for (int i = 0; i < second.rows(); ++i) second(i, i) = second(i, i) == 0.0 ? 0.0 : 3.0 * i;
  const LowerMatrix a = fesd_test::lowerMatrix(first), b = fesd_test::lowerMatrix(second);
  ASSERT_EQ(a.pattern, b.pattern);
  MultifrontalLdlt ldlt(std::make_shared<const SupernodalAnalysis>(a.pattern, FillOrdering::kAmd));
  const Eigen::VectorXd ones = Eigen::VectorXd::Ones(first.rows());
  for (int round = 0; round < 6; ++round) {
    const bool odd = round % 2 == 1;
    const LowerMatrix& lower = odd ? b : a;
    ASSERT_TRUE(ldlt.factor(lower.values.data(), PivotSettings{}).usable());
    Eigen::VectorXd x = (odd ? second : first) * ones;
    ldlt.solve(x.data());
    EXPECT_LT((x - ones).lpNorm<Eigen::Infinity>(), 1e-9);
  }
}

}  // namespace
