#include "fesd_trajopt/linalg/multifrontal_ldlt.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "column_kernels.h"

namespace fesd::linalg {

namespace {

double maxAbs(const double* values, int64_t count) {
  double largest = 0.0;
  for (int64_t i = 0; i < count; ++i) largest = std::max(largest, std::abs(values[i]));
  return largest;
}

}  // namespace

template <class T>
T* MultifrontalLdlt::room(std::vector<T>& buffer, int64_t used, int64_t needed) {
  if (static_cast<int64_t>(buffer.size()) < used + needed) {
    buffer.resize(std::max<int64_t>(used + needed, buffer.size() + buffer.size() / 2));
  }
  return buffer.data() + used;
}

MultifrontalLdlt::MultifrontalLdlt(std::shared_ptr<const SupernodalAnalysis> analysis)
    : analysis_(std::move(analysis)) {
  const int n = analysis_->dimension();
  const int front = analysis_->largestFront();
  values_.resize(analysis_->patternEntries());
  blocks_.resize(analysis_->supernodes().size());
  factor_.resize(analysis_->factorEntries());
  labels_.resize(analysis_->rowIndices().size());
  diagonal_.resize(n);
  off_diagonal_.resize(n);
  front_.resize(analysis_->largestFrontEntries());
  front_labels_.resize(front);
  work_.resize(frontWorkspaceSize(front));
  stack_.resize(analysis_->stackEntries());
  stack_labels_.resize(analysis_->rowIndices().size());
  where_.assign(n, -1);
  updates_.reserve(analysis_->supernodes().size());
  permuted_.resize(n);
  gathered_.resize(front);
  below_.resize(front);
  rhs_.resize(n);
  residual_.resize(n);
  correction_.resize(n);
  best_.resize(n);
}

void MultifrontalLdlt::assemble(int s, int own, int delayed, int rows, const double* values) {
  const SupernodalAnalysis& analysis = *analysis_;
  double* front = front_.data();
  for (int j = 0; j < rows; ++j) {  // the lower triangle: all a front's arithmetic touches
    double* column = front + static_cast<int64_t>(j) * rows;
    std::fill(column + j, column + rows, 0.0);
  }
  // The analysed rows are the own columns, then the rows below; delayed columns sit between.
  const int64_t* starts = analysis.assemblyStarts().data();
  const int* entries = analysis.assemblyEntries().data();
  const int* entry_rows = analysis.assemblyRows().data();
  const int* entry_columns = analysis.assemblyColumns().data();
  for (int64_t k = starts[s]; k < starts[s + 1]; ++k) {
    const int row = entry_rows[k] < own ? entry_rows[k] : entry_rows[k] + delayed;
    front[row + static_cast<int64_t>(entry_columns[k]) * rows] = values[entries[k]];
  }
}

FactorReport MultifrontalLdlt::factor(const double* values, const PivotSettings& settings) {
  const SupernodalAnalysis& analysis = *analysis_;
  const std::vector<Supernode>& supernodes = analysis.supernodes();
  const int* row_indices = analysis.rowIndices().data();
  std::copy(values, values + values_.size(), values_.begin());
  report_ = FactorReport{};
  factorised_ = false;
  for (double value : values_) {
    if (!std::isfinite(value)) {
      report_.finite = false;
      return report_;
    }
  }
  factor_used_ = labels_used_ = 0;
  updates_.clear();
  int64_t stack_used = 0, stack_labels_used = 0, pivots_used = 0;
  for (int s = 0; s < static_cast<int>(supernodes.size()); ++s) {
    const Supernode& node = supernodes[s];
    // The children's updates are the latest on the stack (postorder).
    size_t first_child = updates_.size();
    int delayed = 0;
    while (first_child > 0 && supernodes[updates_[first_child - 1].supernode].parent == s) {
      --first_child;
      delayed += updates_[first_child].delayed;
    }
    const int own = node.columns, summed = own + delayed, rows = summed + node.below();
    int* labels = room(front_labels_, 0, rows);
    room(gathered_, 0, rows);  // the solves' buffers: a front may have grown by delays
    room(below_, 0, rows);
    double* front = room(front_, 0, static_cast<int64_t>(rows) * rows);
    room(work_, 0, frontWorkspaceSize(rows));
    for (int i = 0; i < own; ++i) labels[i] = node.first_column + i;
    int next = own;
    for (size_t c = first_child; c < updates_.size(); ++c) {
      const int* child_labels = stack_labels_.data() + updates_[c].labels;
      std::copy(child_labels, child_labels + updates_[c].delayed, labels + next);
      next += updates_[c].delayed;
    }
    std::copy(row_indices + node.row_offset + own, row_indices + node.row_offset + node.rows,
              labels + summed);
    for (int i = 0; i < rows; ++i) where_[labels[i]] = i;
    assemble(s, own, delayed, rows, values);
    for (size_t c = first_child; c < updates_.size(); ++c) {
      const Update& update = updates_[c];
      const int* child_labels = stack_labels_.data() + update.labels;
      const double* source = stack_.data() + update.values;
      for (int j = 0; j < update.size; ++j) {
        const int pj = where_[child_labels[j]];
        const double* column = source + static_cast<int64_t>(j) * update.size;
        for (int i = j; i < update.size; ++i) {
          const int pi = where_[child_labels[i]];
          const int64_t at = pi >= pj ? pi + static_cast<int64_t>(pj) * rows
                                      : pj + static_cast<int64_t>(pi) * rows;
          front[at] += column[i];
        }
      }
    }
    if (first_child < updates_.size()) {
      stack_used = updates_[first_child].values;
      stack_labels_used = updates_[first_child].labels;
      updates_.resize(first_child);
    }
    PivotSettings front_settings = settings;
    front_settings.eliminate_all = node.parent < 0;
    const FrontResult result = factorFront(front, rows, summed, labels, front_settings,
                                           room(diagonal_, pivots_used, summed),
                                           room(off_diagonal_, pivots_used, summed), work_.data());
    report_.negative += result.negative;
    report_.two_by_two += result.two_by_two;
    report_.zero += result.zero;
    report_.delayed += summed - result.eliminated;
    report_.finite = report_.finite && result.finite;
    if (!report_.usable()) return report_;
    // The eliminated columns' L (lower part) and labels into the factors.
    const int eliminated = result.eliminated;
    Block& block = blocks_[s];
    block.rows = rows;
    block.eliminated = eliminated;
    block.pivots = pivots_used;
    block.values = factor_used_;
    block.labels = labels_used_;
    double* stored = room(factor_, factor_used_, static_cast<int64_t>(rows) * eliminated);
    for (int j = 0; j < eliminated; ++j) {
      const double* column = front + static_cast<int64_t>(j) * rows;
      std::copy(column + j, column + rows, stored + static_cast<int64_t>(j) * rows + j);
    }
    std::copy(labels, labels + rows, room(labels_, labels_used_, rows));
    factor_used_ += static_cast<int64_t>(rows) * eliminated;
    labels_used_ += rows;
    pivots_used += eliminated;
    // The Schur complement (delayed columns first) waits for the parent.
    const int size = rows - eliminated;
    if (size > 0) {
      double* update = room(stack_, stack_used, static_cast<int64_t>(size) * size);
      for (int j = 0; j < size; ++j) {
        const double* column = front + eliminated + static_cast<int64_t>(eliminated + j) * rows;
        std::copy(column + j, column + size, update + static_cast<int64_t>(j) * size + j);
      }
      std::copy(labels + eliminated, labels + rows, room(stack_labels_, stack_labels_used, size));
      updates_.push_back({s, stack_used, stack_labels_used, size, summed - eliminated});
      stack_used += static_cast<int64_t>(size) * size;
      stack_labels_used += size;
    }
  }
  matrix_norm_ = maxAbs(values_.data(), static_cast<int64_t>(values_.size()));
  factorised_ = true;
  return report_;
}

void MultifrontalLdlt::solvePermuted(double* y) const {
  const std::vector<Supernode>& supernodes = analysis_->supernodes();
  double* own = gathered_.data();
  double* below = below_.data();
  for (size_t s = 0; s < supernodes.size(); ++s) {
    const Block& block = blocks_[s];
    const double* l = factor_.data() + block.values;
    const int* labels = labels_.data() + block.labels;
    const int rows = block.rows, count = block.eliminated, rest = rows - count;
    for (int i = 0; i < count; ++i) own[i] = y[labels[i]];
    for (int k = 0; k + 1 < count; ++k) {
      const double* column = l + static_cast<int64_t>(k) * rows;
      for (int i = k + 1; i < count; ++i) own[i] -= column[i] * own[k];
    }
    std::fill(below, below + rest, 0.0);
    kernels::subtractCombination(below, rest, l + count, rows, own, count);
    for (int i = 0; i < rest; ++i) y[labels[count + i]] += below[i];
    // D, 1x1 and 2x2 blocks.
    const double* d = diagonal_.data() + block.pivots;
    const double* e = off_diagonal_.data() + block.pivots;
    for (int i = 0; i < count; ++i) {
      if (e[i] != 0.0) {
        const double det = d[i] * d[i + 1] - e[i] * e[i];
        const double a = own[i], b = own[i + 1];
        own[i] = (d[i + 1] * a - e[i] * b) / det;
        own[i + 1] = (d[i] * b - e[i] * a) / det;
        ++i;
      } else {
        own[i] /= d[i];
      }
    }
    for (int i = 0; i < count; ++i) y[labels[i]] = own[i];
  }
  for (size_t s = supernodes.size(); s-- > 0;) {
    const Block& block = blocks_[s];
    const double* l = factor_.data() + block.values;
    const int* labels = labels_.data() + block.labels;
    const int rows = block.rows, count = block.eliminated, rest = rows - count;
    for (int i = 0; i < count; ++i) own[i] = y[labels[i]];
    for (int i = 0; i < rest; ++i) below[i] = y[labels[count + i]];
    kernels::subtractProducts(own, count, l + count, rows, below, rest);
    for (int k = count - 1; k >= 0; --k) {
      const double* column = l + static_cast<int64_t>(k) * rows;
      own[k] -= kernels::dot(column + k + 1, own + k + 1, count - k - 1);
    }
    for (int i = 0; i < count; ++i) y[labels[i]] = own[i];
  }
}

void MultifrontalLdlt::solve(double* rhs) const {
  if (!factorised_) throw std::logic_error("MultifrontalLdlt::solve before a factorisation");
  const int n = analysis_->dimension();
  const int* index_at = analysis_->indexAt().data();
  for (int k = 0; k < n; ++k) permuted_[k] = rhs[index_at[k]];
  solvePermuted(permuted_.data());
  for (int k = 0; k < n; ++k) rhs[index_at[k]] = permuted_[k];
}

double MultifrontalLdlt::scaledResidual(const double* rhs, const double* x,
                                        double* residual) const {
  const LowerPattern& pattern = analysis_->pattern();
  const int n = pattern.dimension;
  std::copy(rhs, rhs + n, residual);
  for (int j = 0; j < n; ++j) {
    for (int e = pattern.column_starts[j]; e < pattern.column_starts[j + 1]; ++e) {
      const int i = pattern.rows[e];
      residual[i] -= values_[e] * x[j];
      if (i != j) residual[j] -= values_[e] * x[i];
    }
  }
  const double scale = matrix_norm_ * maxAbs(x, n) + maxAbs(rhs, n);
  const double size = maxAbs(residual, n);
  return scale > 0.0 ? size / scale : size;
}

SolveReport MultifrontalLdlt::solveRefined(double* rhs, double tolerance, int max_steps) {
  const int n = analysis_->dimension();
  std::copy(rhs, rhs + n, rhs_.begin());
  solve(rhs);
  SolveReport report;
  report.residual = scaledResidual(rhs_.data(), rhs, residual_.data());
  while (report.residual > tolerance && report.refinement_steps < max_steps) {
    std::copy(rhs, rhs + n, best_.begin());
    std::copy(residual_.begin(), residual_.end(), correction_.begin());
    solve(correction_.data());
    for (int i = 0; i < n; ++i) rhs[i] += correction_[i];
    ++report.refinement_steps;
    const double previous = report.residual;
    report.residual = scaledResidual(rhs_.data(), rhs, residual_.data());
    if (!(report.residual < previous)) {  // no progress (or NaN): keep the better solution
      std::copy(best_.begin(), best_.end(), rhs);
      report.residual = previous;
      break;
    }
    if (report.residual > 0.5 * previous) break;
  }
  return report;
}

}  // namespace fesd::linalg
