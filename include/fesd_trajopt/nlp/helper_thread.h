#pragma once

#include <atomic>
#include <condition_variable>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>

namespace fesd {

/// A second thread that works beside the calling one: runBeside(job) runs job(0) on the caller
/// and job(1) on the helper, if the helper wakes before the caller is done. The jobs share out
/// the work themselves (NlpAssembly's claim chunks of terms): a helper that wakes late does less
/// or none of it, and the caller never waits for it to wake up.
class HelperThread {
 public:
  HelperThread();
  ~HelperThread();
  HelperThread(const HelperThread&) = delete;
  HelperThread& operator=(const HelperThread&) = delete;

  /// Returns when job(0) is done and job(1) done or never begun; rethrows what either threw.
  void runBeside(const std::function<void(int thread)>& job);

 private:
  void serve();

  std::mutex mutex_;
  std::condition_variable wake_;
  const std::function<void(int)>* job_ = nullptr;  ///< offered to the helper; null: none
  bool stopping_ = false;
  std::atomic<bool> helper_busy_{false};  ///< the helper began the job and is not done
  std::exception_ptr failure_;            ///< the helper's
  std::thread thread_;
};

}  // namespace fesd
