#include "fesd_trajopt/solver/heap_policy.h"

#include <malloc.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdlib>

namespace fesd {

namespace {

constexpr std::uintptr_t kHugePage = std::uintptr_t{2} << 20;

}  // namespace

void keepLargeAllocationsInTheHeap() {
  // glibc refuses an mmap threshold above 32 MiB (HEAP_MAX_SIZE / 2): larger blocks are mapped.
  mallopt(M_MMAP_THRESHOLD, 32 << 20);
  mallopt(M_TRIM_THRESHOLD, 1 << 30);
  // The heap grown once by a reserve that stays (no trimming), advised to transparent huge
  // pages: a solve's first touch of its memory then faults once per 2 MiB, not per 4 KiB.
  const auto start = reinterpret_cast<std::uintptr_t>(sbrk(0));
  mallopt(M_TOP_PAD, 64 << 20);
  void* volatile block = malloc(std::size_t{1} << 20);  // more than the heap has: it grows,
  free(block);                                          // by the pad too
  mallopt(M_TOP_PAD, 0);
  const auto end = reinterpret_cast<std::uintptr_t>(sbrk(0));
  const std::uintptr_t first = (start + kHugePage - 1) & ~(kHugePage - 1);
  if (end > first) madvise(reinterpret_cast<void*>(first), end - first, MADV_HUGEPAGE);
}

void releaseFreeMemory(std::size_t keep_bytes) {
  if (mallinfo2().fordblks > keep_bytes) malloc_trim(0);
}

}  // namespace fesd
