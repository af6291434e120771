#include "fesd_trajopt/linalg/supernodal_analysis.h"

#include <algorithm>
#include <memory>
#include <stdexcept>
#include <string>

#include <suitesparse/cholmod.h>

namespace fesd::linalg {

namespace {

/// One CHOLMOD workspace with its objects freed on every path out (CHOLMOD keeps no global
/// state of its own: all of it lives here).
class Cholmod {
 public:
  Cholmod() {
    cholmod_start(&common_);
    common_.print = 0;
  }
  ~Cholmod() {
    if (factor_ != nullptr) cholmod_free_factor(&factor_, &common_);
    if (matrix_ != nullptr) cholmod_free_sparse(&matrix_, &common_);
    cholmod_finish(&common_);
  }
  Cholmod(const Cholmod&) = delete;
  Cholmod& operator=(const Cholmod&) = delete;

  /// The supernodal symbolic factor of the pattern, the fill-reducing order postordered.
  /// With `order`, that order (postordered); else CHOLMOD's choice for `ordering`.
  const cholmod_factor& analyse(const LowerPattern& pattern, FillOrdering ordering,
                                const std::vector<int>* order) {
    common_.supernodal = CHOLMOD_SUPERNODAL;
    common_.postorder = 1;
    if (order != nullptr) {
      common_.nmethods = 1;
      common_.method[0].ordering = CHOLMOD_GIVEN;
    } else if (ordering != FillOrdering::kAuto) {
      common_.nmethods = 1;
      common_.method[0].ordering = ordering == FillOrdering::kAmd ? CHOLMOD_AMD : CHOLMOD_METIS;
    }
    const int n = pattern.dimension;
    matrix_ =
        cholmod_allocate_sparse(n, n, pattern.rows.size(), 1, 1, -1, CHOLMOD_PATTERN, &common_);
    if (matrix_ == nullptr) throw std::runtime_error("CHOLMOD could not allocate the pattern");
    std::copy(pattern.column_starts.begin(), pattern.column_starts.end(),
              static_cast<int*>(matrix_->p));
    std::copy(pattern.rows.begin(), pattern.rows.end(), static_cast<int*>(matrix_->i));
    factor_ = order != nullptr ? cholmod_analyze_p(matrix_, const_cast<int*>(order->data()),
                                                   nullptr, 0, &common_)
                               : cholmod_analyze(matrix_, &common_);
    if (factor_ == nullptr || !factor_->is_super) {
      throw std::runtime_error("CHOLMOD's supernodal analysis failed (status " +
                               std::to_string(common_.status) + ")");
    }
    return *factor_;
  }

 private:
  cholmod_common common_;
  cholmod_sparse* matrix_ = nullptr;
  cholmod_factor* factor_ = nullptr;
};

/// The place of `row` among `count` ascending rows starting at `first`; the structure
/// guarantees it is there.
int placeOf(const int* first, int count, int row) {
  const int* found = std::lower_bound(first, first + count, row);
  if (found == first + count || *found != row) {
    throw std::logic_error("supernodal analysis: a row is missing from its front");
  }
  return static_cast<int>(found - first);
}

}  // namespace

LowerPattern lowerPattern(int dimension, const int* column_starts, const int* rows, int base) {
  if (dimension < 0) throw std::invalid_argument("negative dimension");
  LowerPattern pattern;
  pattern.dimension = dimension;
  pattern.column_starts.resize(dimension + 1);
  for (int j = 0; j <= dimension; ++j) pattern.column_starts[j] = column_starts[j] - base;
  if (pattern.column_starts[0] != 0) throw std::invalid_argument("columns must start at 0");
  for (int j = 0; j < dimension; ++j) {
    if (pattern.column_starts[j + 1] <= pattern.column_starts[j]) {
      throw std::invalid_argument("column " + std::to_string(j) + " has no diagonal entry");
    }
  }
  const int entries = pattern.column_starts[dimension];
  pattern.rows.resize(entries);
  for (int j = 0; j < dimension; ++j) {
    for (int e = pattern.column_starts[j]; e < pattern.column_starts[j + 1]; ++e) {
      const int row = rows[e] - base;
      const bool first = e == pattern.column_starts[j];
      if (row >= dimension || (first && row != j) || (!first && row <= pattern.rows[e - 1])) {
        throw std::invalid_argument("column " + std::to_string(j) +
                                    ": rows must start at the diagonal, ascend and stay in range");
      }
      pattern.rows[e] = row;
    }
  }
  return pattern;
}

SupernodalAnalysis::SupernodalAnalysis(const LowerPattern& pattern, FillOrdering ordering)
    : dimension_(pattern.dimension),
      pattern_(pattern),
      ordering_(ordering),
      pattern_entries_(pattern.nonzeros()) {
  build(pattern, nullptr);
}

SupernodalAnalysis::SupernodalAnalysis(const LowerPattern& pattern, const std::vector<int>& order,
                                       FillOrdering method)
    : dimension_(pattern.dimension),
      pattern_(pattern),
      ordering_(method),
      pattern_entries_(pattern.nonzeros()) {
  if (static_cast<int>(order.size()) != dimension_) {
    throw std::invalid_argument("an order needs one entry per index");
  }
  build(pattern, &order);
}

void SupernodalAnalysis::build(const LowerPattern& pattern, const std::vector<int>* order) {
  const int n = dimension_;
  position_of_.resize(n);
  index_at_.resize(n);
  if (n > 0) {
    Cholmod cholmod;
    const cholmod_factor& symbolic = cholmod.analyse(pattern, ordering_, order);
    if (order == nullptr) {
      ordering_ = symbolic.ordering == CHOLMOD_AMD ? FillOrdering::kAmd : FillOrdering::kMetis;
    }
    const int* perm = static_cast<const int*>(symbolic.Perm);
    for (int k = 0; k < n; ++k) {
      index_at_[k] = perm[k];
      position_of_[perm[k]] = k;
    }
    const int count = static_cast<int>(symbolic.nsuper);
    const int* super = static_cast<const int*>(symbolic.super);
    const int* row_pointer = static_cast<const int*>(symbolic.pi);
    const int* rows = static_cast<const int*>(symbolic.s);
    row_indices_.assign(rows, rows + row_pointer[count]);
    supernodes_.resize(count);
    std::vector<int> supernode_of(n);
    for (int s = 0; s < count; ++s) {
      Supernode& node = supernodes_[s];
      node.first_column = super[s];
      node.columns = super[s + 1] - super[s];
      node.row_offset = row_pointer[s];
      node.rows = row_pointer[s + 1] - row_pointer[s];
      node.factor_offset = factor_entries_;
      factor_entries_ += static_cast<int64_t>(node.rows) * node.columns;
      for (int k = super[s]; k < super[s + 1]; ++k) supernode_of[k] = s;
    }
    for (Supernode& node : supernodes_) {
      if (node.below() > 0) {
        node.parent = supernode_of[row_indices_[node.row_offset + node.columns]];
      }
    }
    buildEntryMap(pattern, supernode_of);
  }
  measure();
}

void SupernodalAnalysis::buildEntryMap(const LowerPattern& pattern,
                                       const std::vector<int>& supernode_of) {
  const int64_t entries = pattern.nonzeros();
  std::vector<int> entry_supernode(entries), entry_row(entries), entry_column(entries);
  assembly_starts_.assign(supernodes_.size() + 1, 0);
  for (int j = 0; j < dimension_; ++j) {
    for (int e = pattern.column_starts[j]; e < pattern.column_starts[j + 1]; ++e) {
      const int a = position_of_[pattern.rows[e]], b = position_of_[j];
      const int row = std::max(a, b), column = std::min(a, b);
      const int s = supernode_of[column];
      const Supernode& node = supernodes_[s];
      entry_supernode[e] = s;
      entry_row[e] = placeOf(row_indices_.data() + node.row_offset, node.rows, row);
      entry_column[e] = column - node.first_column;
      ++assembly_starts_[s + 1];
    }
  }
  for (size_t s = 0; s < supernodes_.size(); ++s) assembly_starts_[s + 1] += assembly_starts_[s];
  assembly_entries_.resize(entries);
  assembly_rows_.resize(entries);
  assembly_columns_.resize(entries);
  std::vector<int64_t> next(assembly_starts_.begin(), assembly_starts_.end() - 1);
  for (int64_t e = 0; e < entries; ++e) {
    const int64_t k = next[entry_supernode[e]]++;
    assembly_entries_[k] = static_cast<int>(e);
    assembly_rows_[k] = entry_row[e];
    assembly_columns_[k] = entry_column[e];
  }
}

void SupernodalAnalysis::measure() {
  // The stack discipline needs every supernode's children to be the latest updates pushed
  // before it: true in a postorder, checked here rather than assumed.
  std::vector<int> stack;
  int64_t stacked = 0;
  std::vector<int> depth(supernodes_.size(), 1);
  for (int s = static_cast<int>(supernodes_.size()) - 1; s >= 0; --s) {
    const int parent = supernodes_[s].parent;
    if (parent >= 0) depth[s] = depth[parent] + 1;
    tree_depth_ = std::max(tree_depth_, depth[s]);
  }
  for (int s = 0; s < static_cast<int>(supernodes_.size()); ++s) {
    const Supernode& node = supernodes_[s];
    while (!stack.empty() && supernodes_[stack.back()].parent == s) {
      const int below = supernodes_[stack.back()].below();
      stacked -= static_cast<int64_t>(below) * below;
      stack.pop_back();
    }
    if (node.parent >= 0) {
      stack.push_back(s);
      stacked += static_cast<int64_t>(node.below()) * node.below();
      stack_entries_ = std::max(stack_entries_, stacked);
    }
    largest_front_ = std::max(largest_front_, node.rows);
    for (int k = 0; k < node.columns; ++k) {
      const double remaining = node.rows - k - 1;
      flops_ += remaining * (remaining + 1) / 2 + remaining;
    }
  }
  for (int s : stack) {
    if (supernodes_[s].parent >= 0) {
      throw std::logic_error("supernodal analysis: the supernodes are not in postorder");
    }
  }
}

int64_t SupernodalAnalysis::largestFrontEntries() const {
  return static_cast<int64_t>(largest_front_) * largest_front_;
}

}  // namespace fesd::linalg
