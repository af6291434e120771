// The sparse LU that Newton's method refactorises with the pivots of its first factorisation
// (solver/repeated_sparse_lu.cpp): solutions against dense LU, reuse of the structure, fresh
// pivots where a reused one became small, tall matrices and singular ones, several right-hand
// sides at once.
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "fesd_trajopt/solver/repeated_sparse_lu.h"

namespace {

/// A random sparse rows x cols matrix with a weak diagonal, so that pivoting matters.
Eigen::SparseMatrix<double> randomMatrix(int rows, int cols, std::mt19937& random) {
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::vector<Eigen::Triplet<double>> entries;
  for (int j = 0; j < cols; ++j) entries.emplace_back(j, j, 1e-3 * value(random));
  for (int e = 0; e < 3 * cols; ++e) {
    entries.emplace_back(random() % rows, random() % cols, value(random));
  }
  Eigen::SparseMatrix<double> matrix(rows, cols);
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  return matrix;
}

/// The relative error of the LU's solution of A x = A x_true.
double solveError(fesd::RepeatedSparseLu& lu, const Eigen::SparseMatrix<double>& matrix) {
  const Eigen::VectorXd truth = Eigen::VectorXd::LinSpaced(matrix.cols(), -1.0, 2.0);
  const Eigen::VectorXd b = matrix * truth;
  std::vector<double> right(b.data(), b.data() + b.size()), x;
  lu.solve(right, x);
  return (Eigen::Map<const Eigen::VectorXd>(x.data(), matrix.cols()) - truth).norm() / truth.norm();
}

TEST(RepeatedSparseLu, SolvesLikeDenseLuAndReusesItsStructureForNewValues) {
  std::mt19937 random(7);
  int reused = 0, tested = 0;
  for (int trial = 0; trial < 40; ++trial) {
    Eigen::SparseMatrix<double> matrix = randomMatrix(30, 30, random);
    // The 1-norm condition number, estimated from a dense LU.
    const double condition = 1.0 / Eigen::PartialPivLU<Eigen::MatrixXd>(matrix).rcond();
    if (!(condition < 1e8)) continue;
    ++tested;
    // Backward stable: the error is rounding times the condition number.
    const double tolerance = 1e-14 * condition;
    fesd::RepeatedSparseLu lu;
    ASSERT_TRUE(lu.factorize(matrix));
    EXPECT_FALSE(lu.reusedStructure());
    EXPECT_LT(solveError(lu, matrix), tolerance);
    // Newton's next Jacobian: the same pattern, values 1 % off.
    std::uniform_real_distribution<double> change(0.99, 1.01);
    for (int e = 0; e < matrix.nonZeros(); ++e) matrix.valuePtr()[e] *= change(random);
    ASSERT_TRUE(lu.factorize(matrix));
    reused += lu.reusedStructure();
    EXPECT_LT(solveError(lu, matrix), 10 * tolerance);
  }
  EXPECT_EQ(reused, tested);
  EXPECT_GE(tested, 10);
}

TEST(RepeatedSparseLu, PivotsAgainWhereAReusedPivotHasBecomeSmall) {
  // [[a, 1], [1, 1]]: for a = 2 the first column pivots on row 0; a = 1e-9 makes that pivot
  // tiny against the 1 below it, so the factorisation pivots on row 1 instead.
  Eigen::SparseMatrix<double> matrix(2, 2);
  std::vector<Eigen::Triplet<double>> entries{{0, 0, 2.0}, {0, 1, 1.0}, {1, 0, 1.0}, {1, 1, 1.0}};
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  fesd::RepeatedSparseLu lu;
  ASSERT_TRUE(lu.factorize(matrix));
  matrix.coeffRef(0, 0) = 1e-9;
  ASSERT_TRUE(lu.factorize(matrix));
  EXPECT_FALSE(lu.reusedStructure());
  EXPECT_LT(solveError(lu, matrix), 1e-12);
  matrix.coeffRef(0, 0) = 2e-9;  // the new pivots hold
  ASSERT_TRUE(lu.factorize(matrix));
  EXPECT_TRUE(lu.reusedStructure());
  EXPECT_LT(solveError(lu, matrix), 1e-12);
}

TEST(RepeatedSparseLu, PicksAsManyRowsAsColumnsOfATallMatrix) {
  // x + y = 3, x - y = -1, 2x + y = 4 (consistent: x = 1, y = 2), the third row the largest.
  Eigen::SparseMatrix<double> matrix(3, 2);
  std::vector<Eigen::Triplet<double>> entries{{0, 0, 1.0},  {0, 1, 1.0}, {1, 0, 1.0},
                                              {1, 1, -1.0}, {2, 0, 2.0}, {2, 1, 1.0}};
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  fesd::RepeatedSparseLu lu;
  ASSERT_TRUE(lu.factorize(matrix));
  EXPECT_EQ(lu.pivoted(0) + lu.pivoted(1) + lu.pivoted(2), 2);
  std::vector<double> right{3.0, -1.0, 4.0}, x;
  lu.solve(right, x);
  ASSERT_EQ(x.size(), 2u);
  EXPECT_NEAR(x[0], 1.0, 1e-15);
  EXPECT_NEAR(x[1], 2.0, 1e-15);
  // More columns than rows is refused.
  EXPECT_FALSE(lu.factorize(Eigen::SparseMatrix<double>(matrix.transpose())));
}

TEST(RepeatedSparseLu, SolvesManyRightHandSidesAsEachOneAlone) {
  std::mt19937 random(11);
  const Eigen::SparseMatrix<double> matrix = randomMatrix(60, 60, random);
  fesd::RepeatedSparseLu lu;
  ASSERT_TRUE(lu.factorize(matrix));
  const int count = 5;
  const Eigen::MatrixXd truth = Eigen::MatrixXd::Random(60, count);
  const Eigen::MatrixXd b = matrix * truth;
  std::vector<double> rows(60 * count), x;
  for (int i = 0; i < 60; ++i) {
    for (int p = 0; p < count; ++p) rows[i * count + p] = b(i, p);
  }
  lu.solve(rows, x, count);
  for (int p = 0; p < count; ++p) {
    std::vector<double> single(b.col(p).data(), b.col(p).data() + 60), one;
    lu.solve(single, one);
    for (int i = 0; i < 60; ++i) {
      EXPECT_DOUBLE_EQ(x[i * count + p], one[i]);
      EXPECT_NEAR(x[i * count + p], truth(i, p), 1e-8 * truth.cwiseAbs().maxCoeff());
    }
  }
}

TEST(RepeatedSparseLu, ReportsASingularMatrix) {
  // The second column is twice the first.
  Eigen::SparseMatrix<double> matrix(2, 2);
  std::vector<Eigen::Triplet<double>> entries{{0, 0, 1.0}, {0, 1, 2.0}, {1, 0, 2.0}, {1, 1, 4.0}};
  matrix.setFromTriplets(entries.begin(), entries.end());
  matrix.makeCompressed();
  fesd::RepeatedSparseLu lu;
  EXPECT_FALSE(lu.factorize(matrix));
  Eigen::SparseMatrix<double> empty_column(2, 2);
  empty_column.insert(0, 0) = 1.0;
  empty_column.insert(1, 0) = 1.0;
  empty_column.makeCompressed();
  EXPECT_FALSE(lu.factorize(empty_column));
}

}  // namespace
