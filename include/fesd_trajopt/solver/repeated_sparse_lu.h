#pragma once

#include <vector>

#include <Eigen/SparseCore>

namespace fesd {

/// A sparse LU factorisation for many matrices of one pattern, as Newton's method factorises its
/// Jacobian again and again: A(:, q) = L U with a fill-reducing column order q (COLAMD) and rows
/// chosen by partial pivoting (left-looking, Gilbert-Peierls). The first factorisation of a
/// pattern finds the order, the pivots and the structure of L and U; later ones with the same
/// pattern only redo the arithmetic on that structure, and pivot afresh when a reused pivot has
/// become small in its column. On the integrator's step systems (~150 unknowns) a refactorisation
/// takes 6-13 us against 55-68 us for Eigen's SparseLU, whose supernodal machinery is made for
/// larger matrices.
///
/// A may have more rows than columns: the pivots then pick as many rows as there are columns,
/// and solve() solves the square system of those rows (the others are for the caller to check).
class RepeatedSparseLu {
 public:
  /// Factorises `a` (compressed, column major). False when it is structurally or numerically
  /// singular (a column without a nonzero pivot) or has fewer rows than columns.
  bool factorize(const Eigen::SparseMatrix<double>& a);
  /// x (size cols) solving the pivot rows of A x = b (b of size rows; it is overwritten).
  void solve(std::vector<double>& b, std::vector<double>& x) const;
  /// The same for `count` right-hand sides at once, row-major: b is rows x count (overwritten),
  /// x cols x count.
  void solve(std::vector<double>& b, std::vector<double>& x, int count) const;

  /// Whether the last factorize() reused the pivots and structure of the one before.
  bool reusedStructure() const { return reused_; }
  /// Whether a row of the last factorised matrix is a pivot row (all but rows - cols are).
  bool pivoted(int row) const { return pivot_step_[row] >= 0; }

 private:
  /// A reused pivot must be at least this fraction of the largest candidate in its column, or
  /// the factorisation pivots again (partial pivoting takes the largest).
  static constexpr double kReusedPivotFraction = 1e-3;

  /// Pattern, column order, pivots and structure from scratch; false when singular.
  bool factorizeWithPivoting(const Eigen::SparseMatrix<double>& a);
  /// The arithmetic on the stored structure; false when a pivot became too small.
  bool refactorize(const Eigen::SparseMatrix<double>& a);
  bool samePattern(const Eigen::SparseMatrix<double>& a) const;
  /// The rows reachable from column `col` of `a` through the columns of L so far, in
  /// topological order, appended to reach_rows_ (a depth-first search, as CSparse's cs_reach).
  void appendReach(const Eigen::SparseMatrix<double>& a, int col);
  /// Column k of L U: scatters A(:, q_k) into work_ and applies the earlier columns of L along
  /// the stored reach.
  void eliminate(const Eigen::SparseMatrix<double>& a, int k);

  int rows_ = 0, cols_ = 0;
  std::vector<int> pattern_starts_, pattern_rows_;  ///< of the factorised matrix
  std::vector<int> column_order_;                   ///< q: the column at position k
  std::vector<int> pivot_row_;                      ///< per position k
  std::vector<int> pivot_step_;                     ///< per row: its position k, or -1
  /// Per position k, rows reach_rows_[reach_start_[k] .. reach_start_[k + 1]) in topological
  /// order: those pivoted before k give U(:, k) (and the columns of L to apply), the others L.
  std::vector<int> reach_start_, reach_rows_;
  std::vector<int> l_start_, l_rows_;  ///< L(:, k) below the pivot, rows of the original numbering
  std::vector<double> l_values_;
  std::vector<int> u_start_, u_steps_;  ///< U(:, k) above the diagonal: positions j < k
  std::vector<double> u_values_, u_diagonal_;
  std::vector<double> work_;  ///< per row, zero between uses
  /// The depth-first search's stack (rows, and where each continues in its column of L), its
  /// output (filled from the end) and marks, per row.
  std::vector<int> dfs_rows_, dfs_next_, dfs_output_;
  std::vector<char> marked_;
  bool has_structure_ = false;  ///< pivots and structure belong to the stored pattern
  bool reused_ = false;
};

}  // namespace fesd
