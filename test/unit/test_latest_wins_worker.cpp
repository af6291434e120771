// The interactive targets' release queue (src/ros/latest_wins_worker.h): one job runs, the newest
// one waits, older waiting ones are dropped.
#include <gtest/gtest.h>

#include <chrono>
#include <condition_variable>
#include <mutex>
#include <thread>
#include <vector>

#include "ros/latest_wins_worker.h"

namespace {

using Worker = fesd_ros::LatestWinsWorker<int>;
constexpr Worker::Clock::duration kNoSpacing{0};

/// A job body that blocks until released, recording the jobs it ran.
struct Gate {
  std::mutex mutex;
  std::condition_variable changed;
  bool open = false, entered = false;
  std::vector<int> ran;

  void run(int job) {
    std::unique_lock<std::mutex> lock(mutex);
    entered = true;
    changed.notify_all();
    changed.wait(lock, [this] { return open; });
    ran.push_back(job);
  }
  void waitUntilEntered() {
    std::unique_lock<std::mutex> lock(mutex);
    changed.wait(lock, [this] { return entered; });
  }
  void release() {
    std::lock_guard<std::mutex> lock(mutex);
    open = true;
    changed.notify_all();
  }
};

TEST(LatestWinsWorker, RunsAPostedJob) {
  std::vector<int> ran;
  fesd_ros::LatestWinsWorker<int> worker([&](int& job) { ran.push_back(job); }, kNoSpacing);
  EXPECT_FALSE(worker.post(7));
  worker.waitUntilIdle();
  EXPECT_EQ(ran, std::vector<int>{7});
  EXPECT_EQ(worker.finished(), 1);
}

TEST(LatestWinsWorker, ABurstWhileAJobRunsRunsOnlyItsLastJob) {
  Gate gate;
  fesd_ros::LatestWinsWorker<int> worker([&](int& job) { gate.run(job); }, kNoSpacing);
  worker.post(0);
  gate.waitUntilEntered();  // job 0 runs: the burst waits behind it
  int superseded = 0;
  for (int job = 1; job <= 20; ++job) superseded += worker.post(job);
  EXPECT_EQ(superseded, 19);  // every post after the first replaced a waiting one
  gate.release();
  worker.waitUntilIdle();
  EXPECT_EQ(gate.ran, (std::vector<int>{0, 20}));
  EXPECT_EQ(worker.finished(), 2);
}

TEST(LatestWinsWorker, JobsStartTheSpacingApartAndPostsMeanwhileCoalesce) {
  std::vector<Worker::Clock::time_point> starts;
  std::vector<int> ran;
  const auto spacing = std::chrono::milliseconds(200);
  Worker worker(
      [&](int& job) {
        starts.push_back(Worker::Clock::now());
        ran.push_back(job);
      },
      spacing);
  worker.post(1);
  while (worker.finished() < 1) std::this_thread::yield();
  for (int job = 2; job <= 5; ++job) worker.post(job);  // within the spacing: one job after it
  worker.waitUntilIdle();
  ASSERT_EQ(ran, (std::vector<int>{1, 5}));
  EXPECT_GE(starts[1] - starts[0], spacing);
}

TEST(LatestWinsWorker, StoppingDropsTheWaitingJobAndFinishesTheRunningOne) {
  Gate gate;
  // Opens the gate once the worker is being destroyed (long after: the destructor's first step
  // takes microseconds).
  std::thread opener;
  {
    fesd_ros::LatestWinsWorker<int> worker([&](int& job) { gate.run(job); }, kNoSpacing);
    worker.post(1);
    gate.waitUntilEntered();
    worker.post(2);
    opener = std::thread([&] {
      std::this_thread::sleep_for(std::chrono::milliseconds(100));
      gate.release();
    });
  }  // the destructor waits for job 1; job 2 never runs
  opener.join();
  EXPECT_EQ(gate.ran, std::vector<int>{1});
}

}  // namespace
