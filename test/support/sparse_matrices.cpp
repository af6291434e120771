#include "support/sparse_matrices.h"

#include <algorithm>
#include <numeric>
#include <random>

namespace fesd_test {

LowerMatrix lowerMatrix(const Eigen::MatrixXd& dense) {
  LowerMatrix matrix;
  const int n = static_cast<int>(dense.rows());
  matrix.pattern.dimension = n;
  matrix.pattern.column_starts.push_back(0);
  for (int j = 0; j < n; ++j) {
    for (int i = j; i < n; ++i) {
      if (i == j || dense(i, j) != 0.0) {
        matrix.pattern.rows.push_back(i);
        matrix.values.push_back(dense(i, j));
      }
    }
    matrix.pattern.column_starts.push_back(static_cast<int>(matrix.pattern.rows.size()));
  }
  return matrix;
}

Eigen::MatrixXd randomKkt(int n, int m, double density, bool convex, double delta, uint32_t seed) {
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  std::uniform_real_distribution<double> chance(0.0, 1.0);
  Eigen::MatrixXd h = Eigen::MatrixXd::Zero(n, n);
  for (int j = 0; j < n; ++j) {
    for (int i = j + 1; i < n; ++i) {
      if (chance(random) < density) h(i, j) = h(j, i) = value(random);
    }
  }
  for (int j = 0; j < n; ++j) {
    h(j, j) = convex ? h.col(j).cwiseAbs().sum() + 0.5 : value(random);
  }
  Eigen::MatrixXd jacobian = Eigen::MatrixXd::Zero(m, n);
  for (int r = 0; r < m; ++r) {
    jacobian(r, r % n) = 1.0 + chance(random);  // full row rank for m <= n
    for (int j = 0; j < n; ++j) {
      if (chance(random) < density) jacobian(r, j) += value(random);
    }
  }
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n + m, n + m);
  kkt.topLeftCorner(n, n) = h;
  kkt.bottomLeftCorner(m, n) = jacobian;
  kkt.topRightCorner(n, m) = jacobian.transpose();
  kkt.bottomRightCorner(m, m) = -delta * Eigen::MatrixXd::Identity(m, m);
  std::vector<int> order(n + m);
  std::iota(order.begin(), order.end(), 0);
  std::shuffle(order.begin(), order.end(), random);
  Eigen::MatrixXd permuted(n + m, n + m);
  for (int i = 0; i < n + m; ++i) {
    for (int j = 0; j < n + m; ++j) permuted(i, j) = kkt(order[i], order[j]);
  }
  return permuted;
}

}  // namespace fesd_test
