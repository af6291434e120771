#include "fesd_trajopt/linalg/front_factorization.h"

#include <algorithm>
#include <cmath>
#include <utility>

#include <Eigen/Core>

#include "column_kernels.h"

namespace fesd::linalg {

namespace {

using Matrix = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic>;
using MatrixMap = Eigen::Map<Matrix, 0, Eigen::OuterStride<>>;
using RowMajorMap =
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>, 0,
               Eigen::OuterStride<>>;

/// Trailing blocks at least this large are updated with Eigen's kernels, smaller ones in loops.
constexpr int kDenseUpdate = 64;

/// The partial factorisation of one front, in panels of up to kFrontBlock pivots: the columns
/// after the panel get the panel's update once it is complete (one dense product); until then a
/// candidate column is brought up to date on its own when it is tested.
class PanelFactorisation {
 public:
  PanelFactorisation(double* front, int rows, int summed, int* labels,
                     const PivotSettings& settings, double* diagonal, double* off_diagonal,
                     double* work)
      : f_(front),
        n_(rows),
        summed_(summed),
        labels_(labels),
        settings_(settings),
        diagonal_(diagonal),
        off_diagonal_(off_diagonal),
        w_(work),
        first_(work + static_cast<int64_t>(rows) * kFrontBlock),
        second_(first_ + rows) {}

  FrontResult run() {
    for (;;) {
      eliminateByThreshold();
      if (!settings_.eliminate_all || k_ >= summed_) break;
      // A root front cannot delay: the best remaining column is taken whatever the threshold.
      if (k_ - panel_start_ + 2 > kFrontBlock) finishPanel();
      if (!takeBestRemaining()) {
        if (result_.finite) result_.zero = summed_ - k_;
        break;
      }
    }
    finishPanel();
    result_.eliminated = k_;
    // Values that overflowed (or a NaN given) end up in the pivots: every test on them fails.
    for (int k = 0; k < k_; ++k) {
      if (!std::isfinite(diagonal_[k]) || !std::isfinite(off_diagonal_[k])) result_.finite = false;
    }
    return result_;
  }

 private:
  /// Takes pivots that pass the threshold test until a whole pass over the remaining fully
  /// summed columns takes none.
  void eliminateByThreshold() {
    int untested_end = summed_;
    bool pivoted_since_retry = false;
    while (k_ < summed_) {
      if (k_ >= untested_end) {
        // Every remaining column failed once; values changed since, so try them again once.
        if (!pivoted_since_retry) break;
        untested_end = summed_;
        pivoted_since_retry = false;
      }
      if (k_ - panel_start_ + 2 > kFrontBlock) finishPanel();
      const int taken = tryPivot(settings_.threshold);
      if (taken > 0) {
        pivoted_since_retry = true;
        continue;
      }
      swap(k_, untested_end - 1);  // failed: to the back, try the next
      --untested_end;
    }
  }

  /// Of the remaining fully summed columns, the one whose diagonal is largest against the rest
  /// of its column goes to position k and is tried with no threshold; false if every pivot
  /// there is zero (or not a number).
  bool takeBestRemaining() {
    int best = -1;
    double best_ratio = -1.0;
    for (int j = k_; j < summed_; ++j) {
      updatedColumn(j, first_);
      const double gamma = largestOffDiagonal(first_, j, -1);
      const double ratio = gamma > 0.0 ? std::abs(first_[j]) / gamma : std::abs(first_[j]);
      if (std::isnan(ratio)) {
        result_.finite = false;
        return false;
      }
      if (ratio > best_ratio) {
        best = j;
        best_ratio = ratio;
      }
    }
    if (best < 0) return false;
    swap(k_, best);
    return tryPivot(0.0) > 0;
  }

  double& at(int i, int j) {
    return i >= j ? f_[i + static_cast<int64_t>(j) * n_] : f_[j + static_cast<int64_t>(i) * n_];
  }

  /// Column j over rows k.. with the current panel's update, into c (indexed by position).
  void updatedColumn(int j, double* c) {
    for (int i = k_; i < j; ++i) c[i] = f_[j + static_cast<int64_t>(i) * n_];
    std::copy(f_ + j + static_cast<int64_t>(j) * n_, f_ + n_ + static_cast<int64_t>(j) * n_, c + j);
    kernels::subtractCombination(c + k_, n_ - k_, f_ + k_ + static_cast<int64_t>(panel_start_) * n_,
                                 n_, wRow(j), k_ - panel_start_);
  }

  /// Largest |c[i]| over i >= k but skip1 and skip2 (in loops without branches: this runs for
  /// every pivot).
  double largestOffDiagonal(const double* c, int skip1, int skip2) const {
    const int low = std::min(skip1, skip2 < 0 ? skip1 : skip2), high = std::max(skip1, skip2);
    auto largestIn = [c](int from, int to) {
      double largest = 0.0;
      for (int i = from; i < to; ++i) largest = std::max(largest, std::abs(c[i]));
      return largest;
    };
    return std::max({largestIn(k_, low), largestIn(low + 1, high), largestIn(high + 1, n_)});
  }

  /// Tries the candidate at position k as a 1x1 pivot, then as a 2x2 pivot with its largest
  /// fully summed partner, with threshold u; returns the pivots taken (0 if neither passes).
  int tryPivot(double u) {
    const int j = k_;
    updatedColumn(j, first_);
    const double a = first_[j];
    const double gamma = largestOffDiagonal(first_, j, -1);
    if (std::abs(a) > settings_.zero && std::abs(a) >= u * gamma) {
      takeOneByOne();
      return 1;
    }
    int partner = -1;
    double partner_size = 0.0;
    for (int i = k_; i < summed_; ++i) {
      if (i != j && std::abs(first_[i]) > partner_size) {
        partner = i;
        partner_size = std::abs(first_[i]);
      }
    }
    if (partner >= 0) {
      updatedColumn(partner, second_);
      const double b = first_[partner], e = second_[partner];
      const double det = a * e - b * b;
      const double gamma_first = largestOffDiagonal(first_, j, partner);
      const double gamma_second = largestOffDiagonal(second_, j, partner);
      if (std::isfinite(det) && std::abs(det) > settings_.zero &&
          u * (std::abs(e) * gamma_first + std::abs(b) * gamma_second) <= std::abs(det) &&
          u * (std::abs(b) * gamma_first + std::abs(a) * gamma_second) <= std::abs(det)) {
        takeTwoByTwo(partner);
        return 2;
      }
    }
    return 0;
  }

  /// The candidate at k (its updated column in first_) becomes a 1x1 pivot.
  void takeOneByOne() {
    const double pivot = first_[k_];
    diagonal_[k_] = pivot;
    off_diagonal_[k_] = 0.0;
    if (pivot < 0.0) ++result_.negative;
    double* column = f_ + static_cast<int64_t>(k_) * n_;
    double* w = w_ + (k_ - panel_start_);
    column[k_] = pivot;
    const double inverse = 1.0 / pivot;
    for (int i = k_ + 1; i < n_; ++i) {
      w[static_cast<int64_t>(i) * kFrontBlock] = first_[i];
      column[i] = first_[i] * inverse;
    }
    ++k_;
  }

  /// The candidate at k and `partner` (updated columns in first_, second_) become a 2x2 pivot.
  void takeTwoByTwo(int partner) {
    if (partner != k_ + 1) {
      swap(k_ + 1, partner);
      std::swap(first_[k_ + 1], first_[partner]);
      std::swap(second_[k_ + 1], second_[partner]);
    }
    const int p = k_, q = k_ + 1;
    const double a = first_[p], b = first_[q], e = second_[q];
    const double det = a * e - b * b;
    diagonal_[p] = a;
    diagonal_[q] = e;
    off_diagonal_[p] = b;
    off_diagonal_[q] = 0.0;
    ++result_.two_by_two;
    if (det < 0.0) {
      ++result_.negative;
    } else if (a < 0.0) {
      result_.negative += 2;
    }
    double* first_column = f_ + static_cast<int64_t>(p) * n_;
    double* second_column = f_ + static_cast<int64_t>(q) * n_;
    double* w_first = w_ + (p - panel_start_);
    first_column[p] = a;
    first_column[q] = 0.0;
    second_column[q] = e;
    w_first[static_cast<int64_t>(q) * kFrontBlock] = b;
    const double inverse_det = 1.0 / det;
    for (int i = q + 1; i < n_; ++i) {
      const double x = first_[i], y = second_[i];
      w_first[static_cast<int64_t>(i) * kFrontBlock] = x;
      w_first[static_cast<int64_t>(i) * kFrontBlock + 1] = y;
      first_column[i] = (x * e - y * b) * inverse_det;
      second_column[i] = (y * a - x * b) * inverse_det;
    }
    k_ += 2;
  }

  /// Symmetric swap of positions p < q (both not yet eliminated), with their labels and the
  /// current panel's W rows.
  void swap(int p, int q) {
    if (p == q) return;
    if (p > q) std::swap(p, q);
    for (int c = 0; c < p; ++c) {
      std::swap(f_[p + static_cast<int64_t>(c) * n_], f_[q + static_cast<int64_t>(c) * n_]);
    }
    for (int i = p + 1; i < q; ++i) std::swap(at(i, p), at(q, i));
    for (int i = q + 1; i < n_; ++i) std::swap(at(i, p), at(i, q));
    std::swap(at(p, p), at(q, q));
    std::swap_ranges(wRow(p), wRow(p) + (k_ - panel_start_), wRow(q));
    std::swap(labels_[p], labels_[q]);
  }

  /// The panel's update of every column after it (lower triangle), then a new panel.
  void finishPanel() {
    const int width = k_ - panel_start_;
    const int rest = n_ - k_;
    if (width > 0 && rest > 0) {
      double* panel = f_ + k_ + static_cast<int64_t>(panel_start_) * n_;
      if (rest >= kDenseUpdate) {
        MatrixMap trailing(f_ + k_ + static_cast<int64_t>(k_) * n_, rest, rest,
                           Eigen::OuterStride<>(n_));
        MatrixMap l(panel, rest, width, Eigen::OuterStride<>(n_));
        RowMajorMap w(wRow(k_), rest, width, Eigen::OuterStride<>(kFrontBlock));
        trailing.triangularView<Eigen::Lower>() -= l * w.transpose();
      } else {
        for (int j = k_; j < n_; ++j) {
          kernels::subtractCombination(f_ + j + static_cast<int64_t>(j) * n_, n_ - j,
                                       panel + (j - k_), n_, wRow(j), width);
        }
      }
    }
    panel_start_ = k_;
  }

  double* f_;
  int n_, summed_;
  int* labels_;
  const PivotSettings& settings_;
  double *diagonal_, *off_diagonal_;
  /// Row i of W = L D of the current panel's pivots (row-major, n x kFrontBlock): the weights
  /// of row i's update, contiguous.
  double* wRow(int i) const { return w_ + static_cast<int64_t>(i) * kFrontBlock; }
  double* w_;
  double *first_, *second_;  ///< the updated columns of the candidates tried
  int k_ = 0, panel_start_ = 0;
  FrontResult result_;
};

}  // namespace

int64_t frontWorkspaceSize(int rows) {
  return static_cast<int64_t>(rows) * (kFrontBlock + 2);
}

FrontResult factorFront(double* front, int rows, int summed, int* labels,
                        const PivotSettings& settings, double* diagonal, double* off_diagonal,
                        double* work) {
  return PanelFactorisation(front, rows, summed, labels, settings, diagonal, off_diagonal, work)
      .run();
}

}  // namespace fesd::linalg
