// Matched orderings of KKT matrices (linalg/kkt_ordering.cpp): every constraint row after a
// primal neighbour, fewer delayed pivots than a plain ordering, METIS where AMD fills much.
#include <algorithm>
#include <memory>
#include <numeric>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "fesd_trajopt/linalg/kkt_ordering.h"
#include "fesd_trajopt/linalg/multifrontal_ldlt.h"
#include "support/sparse_matrices.h"

namespace {

using fesd::linalg::FillOrdering;

/// The constraint rows of a KKT matrix: its zero diagonals.
std::vector<char> zeroDiagonals(const Eigen::MatrixXd& kkt) {
  std::vector<char> constraint(kkt.rows());
  for (int i = 0; i < kkt.rows(); ++i) constraint[i] = kkt(i, i) == 0.0;
  return constraint;
}

TEST(MatchedOrdering, PutsEachConstraintAfterAPrimalNeighbour) {
  for (uint32_t seed = 0; seed < 8; ++seed) {
    const Eigen::MatrixXd kkt = fesd_test::randomKkt(60, 30, 0.05, false, 0.0, seed);
    const fesd_test::LowerMatrix matrix = fesd_test::lowerMatrix(kkt);
    const std::vector<char> constraint = zeroDiagonals(kkt);
    for (const FillOrdering method : {FillOrdering::kAmd, FillOrdering::kMetis}) {
      const std::vector<int> order =
          fesd::linalg::matchedOrdering(matrix.pattern, constraint, method);
      std::vector<int> sorted = order;
      std::sort(sorted.begin(), sorted.end());
      std::vector<int> identity(order.size());
      std::iota(identity.begin(), identity.end(), 0);
      ASSERT_EQ(sorted, identity);
      std::vector<int> position(order.size());
      for (size_t k = 0; k < order.size(); ++k) position[order[k]] = static_cast<int>(k);
      int matched = 0;
      for (int r = 0; r < kkt.rows(); ++r) {
        if (!constraint[r]) continue;
        // Its matched partner comes right before it: a primal neighbour.
        const int before = position[r] > 0 ? order[position[r] - 1] : -1;
        if (before >= 0 && !constraint[before] && kkt(r, before) != 0.0) ++matched;
      }
      // randomKkt gives every constraint r the neighbour r % n, so a greedy matching pairs
      // nearly all of them.
      EXPECT_GE(matched, 25) << "seed " << seed;
    }
  }
}

TEST(AnalyseKkt, MatchedOrderingsDelayFewerPivots) {
  int plain = 0, matched = 0;
  for (uint32_t seed = 0; seed < 8; ++seed) {
    const Eigen::MatrixXd kkt = fesd_test::randomKkt(80, 40, 0.04, false, 0.0, seed);
    const fesd_test::LowerMatrix matrix = fesd_test::lowerMatrix(kkt);
    for (const bool use_matching : {false, true}) {
      const auto analysis =
          use_matching
              ? fesd::linalg::analyseKkt(matrix.pattern, zeroDiagonals(kkt), FillOrdering::kAmd)
              : std::make_shared<const fesd::linalg::SupernodalAnalysis>(matrix.pattern,
                                                                         FillOrdering::kAmd);
      fesd::linalg::MultifrontalLdlt ldlt(analysis);
      const fesd::linalg::FactorReport report =
          ldlt.factor(matrix.values.data(), fesd::linalg::PivotSettings{});
      ASSERT_TRUE(report.usable());
      (use_matching ? matched : plain) += report.delayed;
    }
  }
  EXPECT_GT(plain, 0);
  EXPECT_LT(matched, plain / 2);
}

TEST(AnalyseKkt, AutoTriesMetisWhereAmdFillsMuch) {
  // A random graph of degree ~10: its factor is nearly dense (AMD: many flops per entry), so
  // auto analyses with METIS too and keeps whichever needs fewer flops.
  const Eigen::MatrixXd dense = fesd_test::randomKkt(2000, 200, 0.008, true, 0.0, 11);
  const fesd_test::LowerMatrix matrix = fesd_test::lowerMatrix(dense);
  const std::vector<char> constraint = zeroDiagonals(dense);
  const auto chosen = fesd::linalg::analyseKkt(matrix.pattern, constraint, FillOrdering::kAuto);
  const auto amd = fesd::linalg::analyseKkt(matrix.pattern, constraint, FillOrdering::kAmd);
  const auto metis = fesd::linalg::analyseKkt(matrix.pattern, constraint, FillOrdering::kMetis);
  ASSERT_GT(amd->flops(), 250.0 * amd->factorEntries());  // the rule's case
  EXPECT_EQ(chosen->flops(), std::min(amd->flops(), metis->flops()));
  EXPECT_EQ(amd->ordering(), FillOrdering::kAmd);
  EXPECT_EQ(metis->ordering(), FillOrdering::kMetis);
  // A sparse, banded matrix does not fill much: AMD alone.
  const fesd_test::LowerMatrix sparse =
      fesd_test::lowerMatrix(fesd_test::randomKkt(60, 20, 0.03, true, 0.0, 12));
  const std::vector<char> sparse_constraint(sparse.pattern.dimension, 0);
  EXPECT_EQ(
      fesd::linalg::analyseKkt(sparse.pattern, sparse_constraint, FillOrdering::kAuto)->ordering(),
      FillOrdering::kAmd);
}

// The lower pattern of a 7-point stencil on a side^3 grid (diagonal included).
fesd::linalg::LowerPattern gridPattern(int side) {
  const int n = side * side * side;
  const auto index = [side](int i, int j, int k) { return (i * side + j) * side + k; };
  fesd::linalg::LowerPattern pattern;
  pattern.dimension = n;
  pattern.column_starts.push_back(0);
  for (int i = 0; i < side; ++i) {
    for (int j = 0; j < side; ++j) {
      for (int k = 0; k < side; ++k) {
        pattern.rows.push_back(index(i, j, k));  // rows below the diagonal, ascending
        if (k + 1 < side) pattern.rows.push_back(index(i, j, k + 1));
        if (j + 1 < side) pattern.rows.push_back(index(i, j + 1, k));
        if (i + 1 < side) pattern.rows.push_back(index(i + 1, j, k));
        pattern.column_starts.push_back(static_cast<int>(pattern.rows.size()));
      }
    }
  }
  return pattern;
}

TEST(AnalyseKkt, AutoTriesMetisWhereAmdsFrontsAreLarge) {
  // A 3-D grid: AMD's separators become fronts of hundreds of rows although its flops per factor
  // entry stay under CHOLMOD's rule; auto analyses with METIS as well and keeps the cheaper.
  const fesd::linalg::LowerPattern pattern = gridPattern(14);
  const std::vector<char> primal(pattern.dimension, 0);
  const auto amd = fesd::linalg::analyseKkt(pattern, primal, FillOrdering::kAmd);
  const auto metis = fesd::linalg::analyseKkt(pattern, primal, FillOrdering::kMetis);
  const auto chosen = fesd::linalg::analyseKkt(pattern, primal, FillOrdering::kAuto);
  ASSERT_GE(amd->largestFront(), fesd::linalg::kLargeFront);
  ASSERT_LT(amd->flops(), 250.0 * amd->factorEntries());  // not CHOLMOD's case
  EXPECT_EQ(chosen->flops(), std::min(amd->flops(), metis->flops()));
  EXPECT_LT(metis->flops(), amd->flops());
  EXPECT_EQ(chosen->ordering(), FillOrdering::kMetis);
}

TEST(AnalyseKkt, AMatrixWithoutConstraintsOrEdges) {
  // Diagonal only (an NLP without constraints): every index its own node, nothing to match.
  const fesd_test::LowerMatrix matrix =
      fesd_test::lowerMatrix(Eigen::Vector3d(1.0, 2.0, 3.0).asDiagonal().toDenseMatrix());
  for (const FillOrdering method : {FillOrdering::kAmd, FillOrdering::kMetis}) {
    const auto analysis = fesd::linalg::analyseKkt(matrix.pattern, std::vector<char>(3, 1), method);
    EXPECT_EQ(analysis->factorEntries(), 3);
  }
  EXPECT_THROW(fesd::linalg::matchedOrdering(matrix.pattern, {1}, FillOrdering::kAmd),
               std::invalid_argument);
}

}  // namespace
