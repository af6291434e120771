// The dense partial LDL^T with threshold pivoting of one front (linalg/front_factorization.cpp):
// P A P^T = L D L^T reconstructed, the Schur complement of a partial factorisation, 2x2 pivots
// and delays, the inertia, zero pivots.
#include <algorithm>
#include <cmath>
#include <numeric>
#include <random>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "fesd_trajopt/linalg/front_factorization.h"

namespace {

using fesd::linalg::factorFront;
using fesd::linalg::FrontResult;
using fesd::linalg::PivotSettings;

/// A random symmetric matrix; every `zero_every`-th diagonal entry is zero (as constraint rows).
Eigen::MatrixXd randomSymmetric(int n, int zero_every, uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  Eigen::MatrixXd a(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = j; i < n; ++i) a(i, j) = a(j, i) = value(random);
  }
  for (int i = 0; i < n; i += zero_every) a(i, i) = 0.0;
  return a;
}

struct Factorised {
  FrontResult result;
  Eigen::MatrixXd front;
  std::vector<int> labels;
  std::vector<double> diagonal, off_diagonal;
};

Factorised factorise(const Eigen::MatrixXd& a, int summed, const PivotSettings& settings) {
  const int n = static_cast<int>(a.rows());
  Factorised f;
  f.front = a;
  f.labels.resize(n);
  std::iota(f.labels.begin(), f.labels.end(), 0);
  f.diagonal.assign(n, 0.0);
  f.off_diagonal.assign(n, 0.0);
  std::vector<double> work(fesd::linalg::frontWorkspaceSize(n));
  f.result = factorFront(f.front.data(), n, summed, f.labels.data(), settings, f.diagonal.data(),
                         f.off_diagonal.data(), work.data());
  return f;
}

/// L (rows x eliminated, unit lower, zero inside 2x2 blocks) and D (eliminated square).
void factors(const Factorised& f, Eigen::MatrixXd& l, Eigen::MatrixXd& d) {
  const int n = static_cast<int>(f.front.rows()), e = f.result.eliminated;
  l = Eigen::MatrixXd::Zero(n, e);
  d = Eigen::MatrixXd::Zero(e, e);
  for (int k = 0; k < e; ++k) {
    l(k, k) = 1.0;
    for (int i = k + 1; i < n; ++i) l(i, k) = f.front(i, k);
    d(k, k) = f.diagonal[k];
    if (f.off_diagonal[k] != 0.0) {
      d(k + 1, k) = d(k, k + 1) = f.off_diagonal[k];
      l(k + 1, k) = 0.0;
    }
  }
}

Eigen::MatrixXd permuted(const Eigen::MatrixXd& a, const std::vector<int>& labels) {
  const int n = static_cast<int>(a.rows());
  Eigen::MatrixXd p(n, n);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) p(i, j) = a(labels[i], labels[j]);
  }
  return p;
}

TEST(FactorFront, ReconstructsTheWholeMatrixWithItsInertia) {
  for (uint32_t seed = 0; seed < 20; ++seed) {
    for (const int n : {5, 40, 90}) {  // 90: several panels and the dense update
      for (const double u : {1e-8, 0.01, 0.5}) {
        const Eigen::MatrixXd a = randomSymmetric(n, 3, seed);
        PivotSettings settings;
        settings.threshold = u;
        settings.eliminate_all = true;
        const Factorised f = factorise(a, n, settings);
        ASSERT_TRUE(f.result.finite);
        ASSERT_EQ(f.result.zero, 0);
        ASSERT_EQ(f.result.eliminated, n);
        Eigen::MatrixXd l, d;
        factors(f, l, d);
        const Eigen::MatrixXd p = permuted(a, f.labels);
        EXPECT_LT((l * d * l.transpose() - p).lpNorm<Eigen::Infinity>(), 1e-9 * n)
            << "seed " << seed << " n " << n << " u " << u;
        const Eigen::VectorXd eigenvalues =
            Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd>(a).eigenvalues();
        EXPECT_EQ(f.result.negative, (eigenvalues.array() < 0.0).count());
      }
    }
  }
}

TEST(FactorFront, PartialFactorisationLeavesTheSchurComplement) {
  for (uint32_t seed = 0; seed < 30; ++seed) {
    const int n = seed % 3 == 0 ? 12 : 70, summed = seed % 3 == 0 ? 7 : 45;
    const Eigen::MatrixXd a = randomSymmetric(n, 2, seed);
    PivotSettings settings;
    settings.threshold = seed % 2 == 0 ? 0.1 : 1e-8;
    const Factorised f = factorise(a, summed, settings);
    ASSERT_TRUE(f.result.finite);
    const int e = f.result.eliminated;
    EXPECT_LE(e, summed);
    Eigen::MatrixXd l, d;
    factors(f, l, d);
    const Eigen::MatrixXd p = permuted(a, f.labels);
    // Rows and columns after the eliminated ones: the Schur complement in the trailing block.
    const Eigen::MatrixXd schur = p.bottomRightCorner(n - e, n - e) -
                                  l.bottomRows(n - e) * d * l.bottomRows(n - e).transpose();
    const Eigen::MatrixXd trailing =
        f.front.bottomRightCorner(n - e, n - e).triangularView<Eigen::Lower>().toDenseMatrix();
    const Eigen::MatrixXd schur_lower = schur.triangularView<Eigen::Lower>().toDenseMatrix();
    EXPECT_LT((trailing - schur_lower).lpNorm<Eigen::Infinity>(), 1e-9) << "seed " << seed;
    // The eliminated columns reproduce P A P^T on their rows.
    EXPECT_LT((l.topRows(e) * d * l.transpose() - p.topRows(e)).lpNorm<Eigen::Infinity>(), 1e-9);
    // Labels after the fully summed block are never swapped.
    for (int i = summed; i < n; ++i) EXPECT_EQ(f.labels[i], i);
  }
}

TEST(FactorFront, ZeroDiagonalWithoutPartnerIsDelayed) {
  // [0 0 1; 0 2 0; 1 0 3] with only the first row fully summed: no 1x1 pivot (zero) and no
  // fully summed partner, so it waits.
  Eigen::MatrixXd a(3, 3);
  a << 0, 0, 1, 0, 2, 0, 1, 0, 3;
  const Factorised f = factorise(a, 1, PivotSettings{});
  EXPECT_EQ(f.result.eliminated, 0);
  // With the second row fully summed too the pivot is 2; the zero one still waits.
  const Factorised g = factorise(a, 2, PivotSettings{});
  EXPECT_EQ(g.result.eliminated, 1);
  EXPECT_EQ(g.labels[0], 1);
  // With all three, a 2x2 pivot pairs the zero with row 3.
  PivotSettings all;
  all.eliminate_all = true;
  const Factorised h = factorise(a, 3, all);
  EXPECT_EQ(h.result.eliminated, 3);
  EXPECT_EQ(h.result.two_by_two, 1);
  EXPECT_EQ(h.result.negative, 1);  // eigenvalues of [0 1; 1 3] and 2: one negative
}

TEST(FactorFront, ExactlySingularMatrixHasAZeroPivot) {
  Eigen::MatrixXd a(4, 4);  // two equal constraint rows
  a << 1, 0, 1, 1, 0, 1, 1, 1, 1, 1, 0, 0, 1, 1, 0, 0;
  PivotSettings all;
  all.eliminate_all = true;
  const Factorised f = factorise(a, 4, all);
  EXPECT_TRUE(f.result.finite);
  EXPECT_EQ(f.result.zero, 1);
}

TEST(FactorFront, OverflowIsReportedNotHidden) {
  // Finite entries whose elimination overflows: the Schur complement 1e-200 - 1e400 is -inf.
  Eigen::MatrixXd a(2, 2);
  a << 1e-200, 1e200, 1e200, 1.0;
  PivotSettings all;
  all.eliminate_all = true;
  EXPECT_FALSE(factorise(a, 2, all).result.finite);
  a(1, 1) = std::nan("");
  EXPECT_FALSE(factorise(a, 2, all).result.finite);
}

}  // namespace
