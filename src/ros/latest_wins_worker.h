#pragma once

#include <chrono>
#include <condition_variable>
#include <functional>
#include <mutex>
#include <optional>
#include <thread>
#include <utility>

namespace fesd_ros {

/// Runs jobs on its own thread, one at a time and each at least `spacing` after the one before
/// started, keeping only the newest one waiting: a job posted while another waits replaces it.
/// So a burst of posts shorter than `spacing` costs at most one job in flight and one after it,
/// never a queue (interactive targets: only the last release of a drag matters).
template <class Job>
class LatestWinsWorker {
 public:
  using Clock = std::chrono::steady_clock;

  LatestWinsWorker(std::function<void(Job&)> run, Clock::duration spacing)
      : run_(std::move(run)), spacing_(spacing), thread_([this] { work(); }) {}
  /// Drops the waiting job and waits for the running one to end.
  ~LatestWinsWorker() {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      stopping_ = true;
      waiting_.reset();
    }
    changed_.notify_all();
    thread_.join();
  }
  LatestWinsWorker(const LatestWinsWorker&) = delete;
  LatestWinsWorker& operator=(const LatestWinsWorker&) = delete;

  /// Queues `job` to run after the running one; true when it replaced a job still waiting.
  bool post(Job job) {
    bool superseded = false;
    {
      std::lock_guard<std::mutex> lock(mutex_);
      superseded = waiting_.has_value();
      waiting_ = std::move(job);
    }
    changed_.notify_all();
    return superseded;
  }

  /// Blocks until no job runs or waits (the spacing's wait counts as waiting).
  void waitUntilIdle() {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [this] { return !running_ && !waiting_; });
  }

  /// Jobs run to their end so far.
  int finished() const {
    std::lock_guard<std::mutex> lock(mutex_);
    return finished_;
  }

 private:
  void work() {
    std::unique_lock<std::mutex> lock(mutex_);
    Clock::time_point next_start = Clock::now();
    while (true) {
      changed_.wait(lock, [this] { return stopping_ || waiting_; });
      // Posts until the spacing is over replace the job instead of running after it.
      changed_.wait_until(lock, next_start, [this] { return stopping_; });
      if (stopping_) return;
      next_start = Clock::now() + spacing_;
      Job job = std::move(*waiting_);
      waiting_.reset();
      running_ = true;
      lock.unlock();
      run_(job);
      lock.lock();
      running_ = false;
      ++finished_;
      changed_.notify_all();
    }
  }

  std::function<void(Job&)> run_;
  const Clock::duration spacing_;
  mutable std::mutex mutex_;
  std::condition_variable changed_;
  std::optional<Job> waiting_;
  bool running_ = false;
  bool stopping_ = false;
  int finished_ = 0;
  std::thread thread_;  ///< last: it starts on everything above
};

}  // namespace fesd_ros
