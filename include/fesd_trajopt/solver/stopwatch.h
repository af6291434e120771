#pragma once

#include <chrono>
#include <ctime>

namespace fesd {

/// Wall time and this thread's CPU time since construction (or the last restart).
class Stopwatch {
 public:
  Stopwatch() { restart(); }
  void restart() {
    wall_start_ = std::chrono::steady_clock::now();
    cpu_start_ = threadCpuSeconds();
  }
  double wallSeconds() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - wall_start_).count();
  }
  double cpuSeconds() const { return threadCpuSeconds() - cpu_start_; }

  static double threadCpuSeconds() {
    timespec ts;
    clock_gettime(CLOCK_THREAD_CPUTIME_ID, &ts);
    return ts.tv_sec + 1e-9 * ts.tv_nsec;
  }

 private:
  std::chrono::steady_clock::time_point wall_start_;
  double cpu_start_;
};

}  // namespace fesd
