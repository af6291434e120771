#pragma once

#include <condition_variable>
#include <mutex>

namespace fesd_ros {

/// At most `count` solves at once, whichever way their requests came (services, action goals):
/// a counting semaphore. A Slot holds one for its lifetime.
class SolveSlots {
 public:
  explicit SolveSlots(int count) : free_(count) {}

  class Slot {
   public:
    explicit Slot(SolveSlots& slots) : slots_(slots) {
      std::unique_lock<std::mutex> lock(slots_.mutex_);
      slots_.freed_.wait(lock, [this] { return slots_.free_ > 0; });
      --slots_.free_;
    }
    ~Slot() {
      {
        std::lock_guard<std::mutex> lock(slots_.mutex_);
        ++slots_.free_;
      }
      slots_.freed_.notify_one();
    }
    Slot(const Slot&) = delete;
    Slot& operator=(const Slot&) = delete;

   private:
    SolveSlots& slots_;
  };

 private:
  std::mutex mutex_;
  std::condition_variable freed_;
  int free_;
};

}  // namespace fesd_ros
