// The cache of analyses (linalg/analysis_cache.cpp): one analysis per pattern and constraint
// set, shared; least recently used evicted; safe to use from several threads.
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "fesd_trajopt/linalg/analysis_cache.h"
#include "support/sparse_matrices.h"

namespace {

using fesd::linalg::AnalysisCache;
using fesd::linalg::FillOrdering;

fesd_test::LowerMatrix kkt(uint32_t seed) {
  return fesd_test::lowerMatrix(fesd_test::randomKkt(40, 15, 0.08, false, 0.0, seed));
}

TEST(AnalysisCache, AnalysesEachPatternOnce) {
  AnalysisCache cache(4);
  const fesd_test::LowerMatrix a = kkt(1), b = kkt(2);
  const std::vector<char> none(a.pattern.dimension, 0);
  const auto first = cache.analysis(a.pattern, none, FillOrdering::kAmd);
  const auto again = cache.analysis(a.pattern, none, FillOrdering::kAmd);
  EXPECT_EQ(first.get(), again.get());
  EXPECT_NE(cache.analysis(b.pattern, none, FillOrdering::kAmd).get(), first.get());
  // Another ordering or another set of constraint rows is another analysis.
  EXPECT_NE(cache.analysis(a.pattern, none, FillOrdering::kMetis).get(), first.get());
  std::vector<char> one = none;
  one.back() = 1;
  EXPECT_NE(cache.analysis(a.pattern, one, FillOrdering::kAmd).get(), first.get());
  const AnalysisCache::Statistics statistics = cache.statistics();
  EXPECT_EQ(statistics.hits, 1);
  EXPECT_EQ(statistics.misses, 4);
  EXPECT_EQ(statistics.entries, 4u);
}

TEST(AnalysisCache, EvictsTheLeastRecentlyUsed) {
  AnalysisCache cache(2);
  const fesd_test::LowerMatrix a = kkt(1), b = kkt(2), c = kkt(3);
  const std::vector<char> none(a.pattern.dimension, 0);
  const auto first = cache.analysis(a.pattern, none, FillOrdering::kAmd);
  cache.analysis(b.pattern, none, FillOrdering::kAmd);
  cache.analysis(a.pattern, none, FillOrdering::kAmd);  // a is now the most recent
  cache.analysis(c.pattern, none, FillOrdering::kAmd);  // evicts b
  EXPECT_EQ(cache.analysis(a.pattern, none, FillOrdering::kAmd).get(), first.get());
  EXPECT_EQ(cache.statistics().entries, 2u);
  const int64_t misses = cache.statistics().misses;
  cache.analysis(b.pattern, none, FillOrdering::kAmd);
  EXPECT_EQ(cache.statistics().misses, misses + 1);
  cache.clear();
  EXPECT_EQ(cache.statistics().entries, 0u);
  // An evicted analysis stays valid for whoever still holds it.
  EXPECT_EQ(first->dimension(), a.pattern.dimension);
}

TEST(AnalysisCache, ThreadsGetEqualAnalyses) {
  AnalysisCache cache(8);
  const fesd_test::LowerMatrix a = kkt(4);
  const std::vector<char> none(a.pattern.dimension, 0);
  std::vector<std::shared_ptr<const fesd::linalg::SupernodalAnalysis>> got(6);
  std::vector<std::thread> threads;
  for (size_t t = 0; t < got.size(); ++t) {
    threads.emplace_back([&, t] { got[t] = cache.analysis(a.pattern, none, FillOrdering::kAmd); });
  }
  for (std::thread& thread : threads) thread.join();
  for (const auto& analysis : got) {
    EXPECT_EQ(analysis->indexAt(), got.front()->indexAt());
    EXPECT_EQ(analysis->factorEntries(), got.front()->factorEntries());
  }
  EXPECT_EQ(cache.statistics().hits + cache.statistics().misses, 6);
}

TEST(Fingerprint, DiffersWhenAnEntryMoves) {
  const fesd_test::LowerMatrix a = kkt(5);
  fesd::linalg::LowerPattern moved = a.pattern;
  std::swap(moved.column_starts[1], moved.column_starts[2]);
  EXPECT_NE(fesd::linalg::fingerprint(a.pattern), fesd::linalg::fingerprint(moved));
  EXPECT_EQ(fesd::linalg::fingerprint(a.pattern), fesd::linalg::fingerprint(kkt(5).pattern));
}

}  // namespace
