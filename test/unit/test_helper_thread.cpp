// HelperThread (nlp/helper_thread.cpp): a job shared out between the caller and the helper is
// done once in all, whenever the helper wakes; what either thread throws reaches the caller.
#include <atomic>
#include <stdexcept>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/nlp/helper_thread.h"

namespace {

TEST(HelperThread, EveryItemOfAJobSharedOutIsDoneOnceOnWhicheverThread) {
  fesd::HelperThread helper;
  for (int round = 0; round < 200; ++round) {
    std::vector<std::atomic<int>> done(64);
    std::atomic<int> next{0};
    helper.runBeside([&](int) {
      for (int item; (item = next.fetch_add(1)) < 64;) done[item].fetch_add(1);
    });
    for (const std::atomic<int>& count : done) ASSERT_EQ(count.load(), 1) << "round " << round;
  }
}

TEST(HelperThread, TheCallersShareIsAlwaysItsOwnAndTheHelpersAtMostOnce) {
  fesd::HelperThread helper;
  for (int round = 0; round < 100; ++round) {
    std::atomic<int> caller{0}, beside{0};
    helper.runBeside([&](int thread) { (thread == 0 ? caller : beside).fetch_add(1); });
    EXPECT_EQ(caller.load(), 1);
    EXPECT_LE(beside.load(), 1);  // 0 where the helper woke after the caller was done
  }
}

TEST(HelperThread, WhatEitherThreadThrowsReachesTheCallerAndTheHelperServesOn) {
  fesd::HelperThread helper;
  EXPECT_THROW(helper.runBeside([](int thread) {
    if (thread == 0) throw std::runtime_error("caller");
  }),
               std::runtime_error);
  // The helper's exception: it throws only when it takes the job, so wait for it to.
  std::atomic<bool> taken{false};
  EXPECT_THROW(helper.runBeside([&](int thread) {
    if (thread == 1) {
      taken = true;
      throw std::runtime_error("helper");
    }
    while (!taken) std::this_thread::yield();
  }),
               std::runtime_error);
  std::atomic<int> calls{0};
  helper.runBeside([&](int) { calls.fetch_add(1); });
  EXPECT_GE(calls.load(), 1);
}

}  // namespace
