#include "fesd_trajopt/solver/repeated_sparse_lu.h"

#include <algorithm>
#include <cmath>

#include <Eigen/OrderingMethods>

namespace fesd {

bool RepeatedSparseLu::factorize(const Eigen::SparseMatrix<double>& a) {
  reused_ = false;
  if (!a.isCompressed() || a.rows() < a.cols()) {
    has_structure_ = false;
    pattern_starts_.clear();
    return false;
  }
  if (has_structure_ && samePattern(a) && refactorize(a)) {
    reused_ = true;
    return true;
  }
  return factorizeWithPivoting(a);
}

bool RepeatedSparseLu::samePattern(const Eigen::SparseMatrix<double>& a) const {
  return a.rows() == rows_ && a.cols() == cols_ &&
         static_cast<int>(pattern_starts_.size()) == cols_ + 1 &&
         std::equal(pattern_starts_.begin(), pattern_starts_.end(), a.outerIndexPtr()) &&
         static_cast<int>(pattern_rows_.size()) == a.nonZeros() &&
         std::equal(pattern_rows_.begin(), pattern_rows_.end(), a.innerIndexPtr());
}

bool RepeatedSparseLu::factorizeWithPivoting(const Eigen::SparseMatrix<double>& a) {
  has_structure_ = false;
  if (!samePattern(a)) {
    rows_ = static_cast<int>(a.rows());
    cols_ = static_cast<int>(a.cols());
    pattern_starts_.assign(a.outerIndexPtr(), a.outerIndexPtr() + cols_ + 1);
    pattern_rows_.assign(a.innerIndexPtr(), a.innerIndexPtr() + a.nonZeros());
    Eigen::PermutationMatrix<Eigen::Dynamic, Eigen::Dynamic, int> position;
    Eigen::COLAMDOrdering<int>()(a, position);
    column_order_.resize(cols_);
    for (int col = 0; col < cols_; ++col) column_order_[position.indices()(col)] = col;
  }
  pivot_row_.assign(cols_, -1);
  pivot_step_.assign(rows_, -1);
  reach_start_.assign(1, 0);
  l_start_.assign(1, 0);
  u_start_.assign(1, 0);
  reach_rows_.clear();
  l_rows_.clear();
  l_values_.clear();
  u_steps_.clear();
  u_values_.clear();
  u_diagonal_.assign(cols_, 0.0);
  work_.assign(rows_, 0.0);
  marked_.assign(rows_, 0);
  dfs_rows_.resize(rows_);
  dfs_next_.resize(rows_);
  dfs_output_.resize(rows_);
  for (int k = 0; k < cols_; ++k) {
    appendReach(a, column_order_[k]);
    reach_start_.push_back(static_cast<int>(reach_rows_.size()));
    eliminate(a, k);
    const auto reach_begin = reach_rows_.begin() + reach_start_[k];
    const auto reach_end = reach_rows_.end();
    int pivot = -1;
    double largest = 0.0;
    for (auto r = reach_begin; r != reach_end; ++r) {
      if (pivot_step_[*r] < 0 && std::fabs(work_[*r]) > largest) {
        largest = std::fabs(work_[*r]);
        pivot = *r;
      }
    }
    if (pivot < 0) {
      for (auto r = reach_begin; r != reach_end; ++r) work_[*r] = 0.0;
      return false;
    }
    const double pivot_value = work_[pivot];
    for (auto r = reach_begin; r != reach_end; ++r) {
      if (pivot_step_[*r] >= 0) {
        u_steps_.push_back(pivot_step_[*r]);
        u_values_.push_back(work_[*r]);
      } else if (*r != pivot) {
        l_rows_.push_back(*r);
        l_values_.push_back(work_[*r] / pivot_value);
      }
      work_[*r] = 0.0;
    }
    u_diagonal_[k] = pivot_value;
    pivot_row_[k] = pivot;
    pivot_step_[pivot] = k;
    l_start_.push_back(static_cast<int>(l_rows_.size()));
    u_start_.push_back(static_cast<int>(u_steps_.size()));
  }
  has_structure_ = true;
  return true;
}

bool RepeatedSparseLu::refactorize(const Eigen::SparseMatrix<double>& a) {
  for (int k = 0; k < cols_; ++k) {
    eliminate(a, k);
    const auto reach_begin = reach_rows_.begin() + reach_start_[k];
    const auto reach_end = reach_rows_.begin() + reach_start_[k + 1];
    const double pivot_value = work_[pivot_row_[k]];
    double largest = 0.0;
    for (auto r = reach_begin; r != reach_end; ++r) {
      if (pivot_step_[*r] < 0 || pivot_step_[*r] > k) {
        largest = std::max(largest, std::fabs(work_[*r]));
      }
    }
    if (pivot_value == 0.0 || std::fabs(pivot_value) < kReusedPivotFraction * largest) {
      for (auto r = reach_begin; r != reach_end; ++r) work_[*r] = 0.0;
      return false;
    }
    int u = u_start_[k], l = l_start_[k];
    for (auto r = reach_begin; r != reach_end; ++r) {
      const int step = pivot_step_[*r];
      if (step >= 0 && step < k) {
        u_values_[u++] = work_[*r];
      } else if (step != k) {
        l_values_[l++] = work_[*r] / pivot_value;
      }
      work_[*r] = 0.0;
    }
    u_diagonal_[k] = pivot_value;
  }
  return true;
}

void RepeatedSparseLu::appendReach(const Eigen::SparseMatrix<double>& a, int col) {
  int top = rows_;
  for (Eigen::SparseMatrix<double>::InnerIterator entry(a, col); entry; ++entry) {
    if (marked_[entry.row()]) continue;
    int head = 0;
    dfs_rows_[0] = static_cast<int>(entry.row());
    while (head >= 0) {
      const int row = dfs_rows_[head];
      const int step = pivot_step_[row];
      if (!marked_[row]) {
        marked_[row] = 1;
        dfs_next_[head] = step < 0 ? 0 : l_start_[step];
      }
      const int end = step < 0 ? 0 : l_start_[step + 1];
      bool done = true;
      for (int p = dfs_next_[head]; p < end; ++p) {
        if (marked_[l_rows_[p]]) continue;
        dfs_next_[head] = p + 1;
        dfs_rows_[++head] = l_rows_[p];
        done = false;
        break;
      }
      if (done) {
        --head;
        dfs_output_[--top] = row;
      }
    }
  }
  for (int p = top; p < rows_; ++p) {
    reach_rows_.push_back(dfs_output_[p]);
    marked_[dfs_output_[p]] = 0;
  }
}

void RepeatedSparseLu::eliminate(const Eigen::SparseMatrix<double>& a, int k) {
  for (Eigen::SparseMatrix<double>::InnerIterator entry(a, column_order_[k]); entry; ++entry) {
    work_[entry.row()] = entry.value();
  }
  for (int p = reach_start_[k]; p < reach_start_[k + 1]; ++p) {
    const int row = reach_rows_[p], step = pivot_step_[row];
    if (step < 0 || step >= k) continue;  // not an earlier pivot: an entry of L(:, k)
    const double value = work_[row];
    if (value == 0.0) continue;
    for (int q = l_start_[step]; q < l_start_[step + 1]; ++q) {
      work_[l_rows_[q]] -= l_values_[q] * value;
    }
  }
}

void RepeatedSparseLu::solve(std::vector<double>& b, std::vector<double>& x) const {
  solve(b, x, 1);
}

void RepeatedSparseLu::solve(std::vector<double>& b, std::vector<double>& x, int count) const {
  // Row-major: each elimination updates `count` adjacent values, one pass over L and U; x is the
  // work space in pivot order, b (rows >= cols) takes it before it is put in column order.
  const auto row = [count](std::vector<double>& v, int i) { return v.data() + i * count; };
  x.resize(static_cast<size_t>(cols_) * count);
  for (int k = 0; k < cols_; ++k) {
    const double* value = row(b, pivot_row_[k]);
    for (int q = l_start_[k]; q < l_start_[k + 1]; ++q) {
      double* target = row(b, l_rows_[q]);
      for (int p = 0; p < count; ++p) target[p] -= l_values_[q] * value[p];
    }
    std::copy(value, value + count, row(x, k));
  }
  for (int k = cols_ - 1; k >= 0; --k) {
    double* value = row(x, k);
    for (int p = 0; p < count; ++p) value[p] /= u_diagonal_[k];
    for (int q = u_start_[k]; q < u_start_[k + 1]; ++q) {
      double* target = row(x, u_steps_[q]);
      for (int p = 0; p < count; ++p) target[p] -= u_values_[q] * value[p];
    }
  }
  std::copy(x.begin(), x.end(), b.begin());
  for (int k = 0; k < cols_; ++k) std::copy(row(b, k), row(b, k) + count, row(x, column_order_[k]));
}

}  // namespace fesd
