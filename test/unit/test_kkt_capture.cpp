// What a KktCapture sees of a solve (solver/kkt_capture.cpp): our LDL^T's analyses,
// factorisations and solves in this thread only, the first matrices kept, nesting.
#include <thread>

#include <gtest/gtest.h>

#include "fesd_trajopt/solver/kkt_capture.h"
#include "support/corner_mpcc.h"

namespace {

TEST(KktCapture, CountsAndKeepsTheKktSystemsOfASolve) {
  fesd::KktCapture capture(2);
  ASSERT_EQ(fesd::KktCapture::active(), &capture);
  fesd_test::CornerMpcc<> problem;
  const fesd::MpccReport report = problem.solve();
  ASSERT_EQ(report.status, fesd::SolveStatus::kSuccess);
  const fesd::KktCapture::Totals& totals = capture.totals();
  // One analysis per relaxed NLP (Ipopt builds its linear solver anew for each), at least one
  // factorisation and solve per Ipopt iteration.
  EXPECT_EQ(totals.analyses, static_cast<int>(report.history.size()));
  EXPECT_GE(totals.factorisations, report.iterations);
  EXPECT_GE(totals.solves, totals.factorisations);
  EXPECT_GT(totals.factor_seconds, 0.0);
  ASSERT_EQ(capture.matrices().size(), 2u);
  const fesd::KktCapture::Matrix& first = capture.matrices().front();
  EXPECT_EQ(static_cast<int64_t>(first.values.size()), first.pattern.nonzeros());
  EXPECT_EQ(static_cast<int>(first.constraint.size()), first.pattern.dimension);
  EXPECT_EQ(totals.largest_dimension, first.pattern.dimension);
}

TEST(KktCapture, WatchesOnlyItsThreadAndNests) {
  fesd::KktCapture outer;
  {
    fesd::KktCapture inner;
    EXPECT_EQ(fesd::KktCapture::active(), &inner);
    fesd_test::CornerMpcc<> problem;
    problem.solve();
    EXPECT_GT(inner.totals().factorisations, 0);
  }
  EXPECT_EQ(fesd::KktCapture::active(), &outer);
  EXPECT_EQ(outer.totals().factorisations, 0);
  std::thread other([] {
    EXPECT_EQ(fesd::KktCapture::active(), nullptr);
    fesd_test::CornerMpcc<> problem;
    problem.solve();
  });
  other.join();
  EXPECT_EQ(outer.totals().factorisations, 0);
}

}  // namespace
