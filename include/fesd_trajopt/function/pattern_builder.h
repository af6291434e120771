#pragma once

#include <map>
#include <utility>

#include "fesd_trajopt/function/smooth_function.h"

namespace fesd {

/// Deduplicating builder for a sparsity pattern: (row, col) -> its slot, added on first use.
class PatternBuilder {
 public:
  int slot(int row, int col) {
    const auto inserted = index_.emplace(std::make_pair(row, col), pattern.nonzeros());
    if (inserted.second) pattern.add(row, col);
    return inserted.first->second;
  }
  SparsityPattern pattern;

 private:
  std::map<std::pair<int, int>, int> index_;
};

}  // namespace fesd
