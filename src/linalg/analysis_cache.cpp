#include "fesd_trajopt/linalg/analysis_cache.h"

#include "fesd_trajopt/linalg/kkt_ordering.h"

namespace fesd::linalg {

namespace {

void mix(uint64_t& hash, uint64_t value) {
  constexpr uint64_t kPrime = 1099511628211ull;
  hash ^= value;
  hash *= kPrime;
}

}  // namespace

uint64_t fingerprint(const LowerPattern& pattern) {
  uint64_t hash = 14695981039346656037ull;
  mix(hash, static_cast<uint64_t>(pattern.dimension));
  for (int start : pattern.column_starts) mix(hash, static_cast<uint32_t>(start));
  for (int row : pattern.rows) mix(hash, static_cast<uint32_t>(row));
  return hash;
}

std::shared_ptr<const SupernodalAnalysis> AnalysisCache::analysis(
    const LowerPattern& pattern, const std::vector<char>& constraint, FillOrdering ordering) {
  const uint64_t key = fingerprint(pattern);
  {
    std::lock_guard<std::mutex> lock(mutex_);
    for (auto entry = entries_.begin(); entry != entries_.end(); ++entry) {
      if (entry->fingerprint == key && entry->ordering == ordering &&
          entry->constraint == constraint && entry->analysis->pattern() == pattern) {
        entries_.splice(entries_.begin(), entries_, entry);
        ++statistics_.hits;
        return entries_.front().analysis;
      }
    }
    ++statistics_.misses;
  }
  // Analysed outside the lock: other patterns need not wait (two threads may analyse the same
  // pattern at once; both results are equal).
  std::shared_ptr<const SupernodalAnalysis> analysed = analyseKkt(pattern, constraint, ordering);
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.push_front({key, ordering, constraint, analysed});
  while (entries_.size() > capacity_) entries_.pop_back();
  return analysed;
}

AnalysisCache::Statistics AnalysisCache::statistics() const {
  std::lock_guard<std::mutex> lock(mutex_);
  Statistics statistics = statistics_;
  statistics.entries = entries_.size();
  return statistics;
}

void AnalysisCache::clear() {
  std::lock_guard<std::mutex> lock(mutex_);
  entries_.clear();
  statistics_ = Statistics{};
}

AnalysisCache& AnalysisCache::process() {
  static AnalysisCache cache;
  return cache;
}

}  // namespace fesd::linalg
