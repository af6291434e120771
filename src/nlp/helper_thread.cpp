#include "fesd_trajopt/nlp/helper_thread.h"

namespace fesd {
namespace {

/// job(thread), and what it threw.
std::exception_ptr run(const std::function<void(int)>& job, int thread) {
  try {
    job(thread);
  } catch (...) {
    return std::current_exception();
  }
  return nullptr;
}

}  // namespace

HelperThread::HelperThread() : thread_([this] { serve(); }) {}

HelperThread::~HelperThread() {
  {
    // Notified under the lock, so that race checkers (helgrind) see the hand-over as one.
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
    wake_.notify_one();
  }
  thread_.join();
}

void HelperThread::runBeside(const std::function<void(int thread)>& job) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = &job;
    failure_ = nullptr;
    wake_.notify_one();
  }
  const std::exception_ptr own = run(job, 0);
  {
    // Withdrawn if the helper has not taken it; else it is busy on its last share.
    std::lock_guard<std::mutex> lock(mutex_);
    job_ = nullptr;
  }
  while (helper_busy_.load(std::memory_order_acquire)) std::this_thread::yield();
  if (own) std::rethrow_exception(own);
  if (failure_) std::rethrow_exception(failure_);
}

void HelperThread::serve() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    wake_.wait(lock, [this] { return stopping_ || job_ != nullptr; });
    if (stopping_) return;
    const std::function<void(int)>& job = *job_;
    job_ = nullptr;  // taken
    helper_busy_.store(true, std::memory_order_relaxed);
    lock.unlock();
    const std::exception_ptr failure = run(job, 1);
    lock.lock();
    failure_ = failure;
    helper_busy_.store(false, std::memory_order_release);
  }
}

}  // namespace fesd
