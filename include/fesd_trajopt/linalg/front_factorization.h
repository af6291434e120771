#pragma once

#include <cstdint>

namespace fesd::linalg {

/// Threshold pivoting as in MA57/MA97: a 1x1 pivot a_kk is taken if |a_kk| >= u max_i |a_ik|
/// over the rest of its column; otherwise a 2x2 pivot with the fully summed row that is largest
/// in that column, if the 2x2 test passes; otherwise the column waits (is delayed to the parent
/// front, where more rows are fully summed).
struct PivotSettings {
  double threshold = 1e-8;  ///< u: 0 takes every pivot that is not zero
  double zero = 1e-20;      ///< pivots (or 2x2 determinants) at most this in magnitude are zero
  /// Eliminate every fully summed column (a root front: nothing to delay to); a column with no
  /// pivot above `zero` then counts as a zero pivot.
  bool eliminate_all = false;
};

/// What the partial factorisation of one front did.
struct FrontResult {
  int eliminated = 0;  ///< pivots taken (a 2x2 pivot counts 2)
  int negative = 0;    ///< negative eigenvalues of D
  int two_by_two = 0;  ///< 2x2 pivots
  int zero = 0;        ///< zero pivots (only when eliminating all): the matrix is singular
  bool finite = true;
};

/// Workspace for factorFront of fronts with at most `rows` rows.
int64_t frontWorkspaceSize(int rows);

/// Partial LDL^T with pivoting of a dense symmetric front (column-major, `rows` x `rows`, lower
/// triangle used) whose first `summed` rows are fully summed. Rows and columns are swapped
/// within the fully summed block as pivots are chosen; `labels` (one per row) are swapped with
/// them. On return the first `eliminated` columns hold L below the diagonal (unit diagonal, zero
/// inside 2x2 blocks), D is in `diagonal` (per pivot) and `off_diagonal` (at the first position
/// of a 2x2 block, else 0), and the trailing block from `eliminated` on holds the Schur
/// complement: the delayed columns first, then the other rows.
FrontResult factorFront(double* front, int rows, int summed, int* labels,
                        const PivotSettings& settings, double* diagonal, double* off_diagonal,
                        double* work);

/// Columns eliminated together before their update of the rest of the front.
constexpr int kFrontBlock = 32;

}  // namespace fesd::linalg
