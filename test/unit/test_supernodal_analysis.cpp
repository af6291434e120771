// The symbolic analysis (linalg/supernodal_analysis.cpp): patterns read and checked, supernodes
// that cover every column in a postorder, every input entry placed in its front, a given order
// kept up to the postorder.
#include <algorithm>
#include <numeric>
#include <set>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "fesd_trajopt/linalg/supernodal_analysis.h"
#include "support/sparse_matrices.h"

namespace {

using fesd::linalg::FillOrdering;
using fesd::linalg::LowerPattern;
using fesd::linalg::SupernodalAnalysis;

TEST(LowerPattern, ReadsOneBasedColumnsAndRefusesMalformedOnes) {
  // [x . .; x x .; . x x] lower triangle, 1-based as Ipopt hands it to MA97.
  const int starts[] = {1, 3, 5, 6}, rows[] = {1, 2, 2, 3, 3};
  const LowerPattern pattern = fesd::linalg::lowerPattern(3, starts, rows, 1);
  EXPECT_EQ(pattern.column_starts, (std::vector<int>{0, 2, 4, 5}));
  EXPECT_EQ(pattern.rows, (std::vector<int>{0, 1, 1, 2, 2}));
  const int no_diagonal[] = {2, 2, 3, 3, 3};
  EXPECT_THROW(fesd::linalg::lowerPattern(3, starts, no_diagonal, 1), std::invalid_argument);
  const int unsorted_starts[] = {1, 4, 5, 6}, unsorted[] = {1, 3, 2, 2, 3};
  EXPECT_THROW(fesd::linalg::lowerPattern(3, unsorted_starts, unsorted, 1), std::invalid_argument);
  const int empty_column[] = {1, 3, 3, 4};
  EXPECT_THROW(fesd::linalg::lowerPattern(3, empty_column, rows, 1), std::invalid_argument);
  EXPECT_THROW(fesd::linalg::lowerPattern(-1, starts, rows, 1), std::invalid_argument);
}

void expectConsistent(const SupernodalAnalysis& analysis, const LowerPattern& pattern) {
  const int n = pattern.dimension;
  // The order is a permutation and its inverse.
  std::vector<int> sorted = analysis.indexAt();
  std::sort(sorted.begin(), sorted.end());
  std::vector<int> identity(n);
  std::iota(identity.begin(), identity.end(), 0);
  ASSERT_EQ(sorted, identity);
  for (int k = 0; k < n; ++k) EXPECT_EQ(analysis.positionOf()[analysis.indexAt()[k]], k);
  // Supernodes cover the columns in order; children come before parents; each front starts
  // with its own columns and its other rows are rows of its parent.
  int next_column = 0;
  for (int s = 0; s < static_cast<int>(analysis.supernodes().size()); ++s) {
    const fesd::linalg::Supernode& node = analysis.supernodes()[s];
    EXPECT_EQ(node.first_column, next_column);
    next_column += node.columns;
    const int* rows = analysis.rowIndices().data() + node.row_offset;
    for (int k = 0; k < node.columns; ++k) EXPECT_EQ(rows[k], node.first_column + k);
    EXPECT_TRUE(std::is_sorted(rows, rows + node.rows));
    if (node.parent < 0) {
      EXPECT_EQ(node.below(), 0);
      continue;
    }
    EXPECT_GT(node.parent, s);
    const fesd::linalg::Supernode& parent = analysis.supernodes()[node.parent];
    const std::set<int> parent_rows(
        analysis.rowIndices().begin() + parent.row_offset,
        analysis.rowIndices().begin() + parent.row_offset + parent.rows);
    for (int i = node.columns; i < node.rows; ++i) EXPECT_EQ(parent_rows.count(rows[i]), 1u);
  }
  EXPECT_EQ(next_column, n);
  // Every input entry lands in its supernode's front, at its own row and column.
  std::vector<int> placed(pattern.nonzeros(), 0);
  for (size_t s = 0; s < analysis.supernodes().size(); ++s) {
    const fesd::linalg::Supernode& node = analysis.supernodes()[s];
    for (int64_t k = analysis.assemblyStarts()[s]; k < analysis.assemblyStarts()[s + 1]; ++k) {
      const int entry = analysis.assemblyEntries()[k];
      ++placed[entry];
      const int column =
          std::upper_bound(pattern.column_starts.begin(), pattern.column_starts.end(), entry) -
          pattern.column_starts.begin() - 1;
      const int a = analysis.positionOf()[pattern.rows[entry]];
      const int b = analysis.positionOf()[column];
      EXPECT_EQ(node.first_column + analysis.assemblyColumns()[k], std::min(a, b));
      EXPECT_EQ(analysis.rowIndices()[node.row_offset + analysis.assemblyRows()[k]],
                std::max(a, b));
    }
  }
  for (int count : placed) EXPECT_EQ(count, 1);
}

TEST(SupernodalAnalysis, CoversEveryColumnAndEntryInBothOrderings) {
  for (uint32_t seed = 0; seed < 6; ++seed) {
    const fesd_test::LowerMatrix matrix =
        fesd_test::lowerMatrix(fesd_test::randomKkt(80, 30, 0.05, false, 0.0, seed));
    for (const FillOrdering ordering :
         {FillOrdering::kAuto, FillOrdering::kAmd, FillOrdering::kMetis}) {
      const SupernodalAnalysis analysis(matrix.pattern, ordering);
      expectConsistent(analysis, matrix.pattern);
      EXPECT_NE(analysis.ordering(), FillOrdering::kAuto);
      EXPECT_GE(analysis.factorEntries(), matrix.pattern.nonzeros());
      EXPECT_GT(analysis.flops(), 0.0);
      EXPECT_GE(analysis.largestFrontEntries(),
                static_cast<int64_t>(analysis.largestFront()) * analysis.largestFront());
    }
  }
}

TEST(SupernodalAnalysis, KeepsAGivenOrder) {
  // A tridiagonal matrix in its natural order: a chain, which the postorder leaves as it is.
  const int n = 50;
  Eigen::MatrixXd tridiagonal = Eigen::MatrixXd::Zero(n, n);
  for (int i = 0; i < n; ++i) {
    tridiagonal(i, i) = 2.0;
    if (i + 1 < n) tridiagonal(i + 1, i) = tridiagonal(i, i + 1) = -1.0;
  }
  const fesd_test::LowerMatrix matrix = fesd_test::lowerMatrix(tridiagonal);
  std::vector<int> natural(n);
  std::iota(natural.begin(), natural.end(), 0);
  const SupernodalAnalysis analysis(matrix.pattern, natural, FillOrdering::kAmd);
  expectConsistent(analysis, matrix.pattern);
  EXPECT_EQ(analysis.indexAt(), natural);
  // Supernodes may add explicit zeros (amalgamation), never fewer entries than the fill.
  EXPECT_GE(analysis.factorEntries(), 2 * n - 1);
  EXPECT_EQ(analysis.ordering(), FillOrdering::kAmd);
  EXPECT_THROW(SupernodalAnalysis(matrix.pattern, std::vector<int>(n - 1), FillOrdering::kAmd),
               std::invalid_argument);
}

TEST(SupernodalAnalysis, AnEmptyMatrixHasNoSupernodes) {
  const SupernodalAnalysis analysis(LowerPattern{0, {0}, {}}, FillOrdering::kAuto);
  EXPECT_EQ(analysis.dimension(), 0);
  EXPECT_TRUE(analysis.supernodes().empty());
}

}  // namespace
