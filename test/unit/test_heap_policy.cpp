// The heap policy of the programs that solve (solver/heap_policy.cpp; test_main applies it):
// blocks up to 32 MiB from the heap, a reserve advised to huge pages, trimming only when much is
// free.
#include <malloc.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "fesd_trajopt/solver/heap_policy.h"

namespace {

/// Whether the heap's mapping that holds `address` is advised to huge pages ("hg" in smaps).
bool hugePagesAdvisedAt(const void* address) {
  std::ifstream smaps("/proc/self/smaps");
  std::string line;
  const auto at = reinterpret_cast<std::uintptr_t>(address);
  bool inside = false;
  while (std::getline(smaps, line)) {
    std::uintptr_t begin = 0, end = 0;
    char permissions[5] = {};
    if (std::sscanf(line.c_str(), "%lx-%lx %4s", &begin, &end, permissions) == 3) {
      inside = begin <= at && at < end;  // a mapping's first line
    } else if (inside && line.rfind("VmFlags:", 0) == 0) {
      return line.find(" hg") != std::string::npos;
    }
  }
  return false;
}

TEST(HeapPolicy, LargeBlocksComeFromTheHugePageHeap) {
  const auto heap_end = reinterpret_cast<std::uintptr_t>(sbrk(0));
  void* block = malloc(std::size_t{16} << 20);
  ASSERT_NE(block, nullptr);
  std::memset(block, 1, std::size_t{16} << 20);
  EXPECT_LE(reinterpret_cast<std::uintptr_t>(block), heap_end);  // not a fresh map above it
  EXPECT_TRUE(hugePagesAdvisedAt(static_cast<char*>(block) + (std::size_t{8} << 20)));
  free(block);
}

TEST(HeapPolicy, TrimsOnlyWhenMuchIsFree) {
  void* block = malloc(std::size_t{8} << 20);
  std::memset(block, 1, std::size_t{8} << 20);
  free(block);
  const std::size_t free_before = mallinfo2().fordblks;
  ASSERT_GE(free_before, std::size_t{8} << 20);
  fesd::releaseFreeMemory();  // 256 MiB kept by default: nothing happens
  EXPECT_EQ(mallinfo2().fordblks, free_before);
  fesd::releaseFreeMemory(0);  // trims: the free pages go back (the heap's bookkeeping stays)
  EXPECT_LE(mallinfo2().fordblks, free_before);
}

}  // namespace
