#pragma once

#include <cstdint>
#include <list>
#include <memory>
#include <mutex>
#include <vector>

#include "fesd_trajopt/linalg/supernodal_analysis.h"

namespace fesd::linalg {

/// Analyses of the patterns factorised lately, so that the ordering and symbolic work is done
/// once per sparsity structure: across Ipopt iterations, homotopy steps, accuracy rungs and
/// replans that keep their discretisation. Thread-safe; the analyses are immutable and shared.
class AnalysisCache {
 public:
  explicit AnalysisCache(size_t capacity = 16) : capacity_(capacity) {}

  /// The analysis of a KKT matrix's `pattern` with its `constraint` rows in `ordering`
  /// (analyseKkt): the cached one if pattern and constraints are equal, else a new one (which
  /// then evicts the least recently used beyond the capacity).
  std::shared_ptr<const SupernodalAnalysis> analysis(const LowerPattern& pattern,
                                                     const std::vector<char>& constraint,
                                                     FillOrdering ordering);

  struct Statistics {
    int64_t hits = 0, misses = 0;
    size_t entries = 0;
  };
  Statistics statistics() const;
  void clear();

  /// The process' cache, used by the linear solver Ipopt calls (whose interface passes no
  /// context of ours).
  static AnalysisCache& process();

 private:
  struct Entry {
    uint64_t fingerprint;
    FillOrdering ordering;
    std::vector<char> constraint;
    std::shared_ptr<const SupernodalAnalysis> analysis;
  };

  size_t capacity_;
  mutable std::mutex mutex_;
  std::list<Entry> entries_;  ///< most recently used first
  Statistics statistics_;
};

/// A hash of a pattern (FNV-1a, word by word, over its dimension, column starts and rows).
uint64_t fingerprint(const LowerPattern& pattern);

}  // namespace fesd::linalg
