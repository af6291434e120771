#pragma once

#include <cstdint>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/linalg/supernodal_analysis.h"

namespace fesd_test {

/// A symmetric matrix as the linear solvers take it: its lower-triangle pattern (every diagonal
/// entry present) and the values in the pattern's entry order.
struct LowerMatrix {
  fesd::linalg::LowerPattern pattern;
  std::vector<double> values;
};

/// The lower triangle of a dense symmetric matrix: its nonzeros and the whole diagonal.
LowerMatrix lowerMatrix(const Eigen::MatrixXd& dense);

/// A random KKT matrix [H J^T; J -delta I] (H: n x n, sparse, symmetric, `convex` makes it
/// positive definite; J: m x n, sparse, full row rank), its rows and columns randomly permuted
/// (so that constraint rows are not all last).
Eigen::MatrixXd randomKkt(int n, int m, double density, bool convex, double delta, uint32_t seed);

}  // namespace fesd_test
