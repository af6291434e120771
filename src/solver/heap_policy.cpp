#include "fesd_trajopt/solver/heap_policy.h"

#include <malloc.h>

namespace fesd {

void keepLargeAllocationsInTheHeap() {
  constexpr int kLargest = 1 << 30;  // bytes: MUMPS' workspaces stay below it
  mallopt(M_ARENA_MAX, 1);           // solves run in worker threads: one heap for all of them
  mallopt(M_MMAP_THRESHOLD, kLargest);
  mallopt(M_TRIM_THRESHOLD, kLargest);
}

void releaseFreeMemory() {
  malloc_trim(0);
}

}  // namespace fesd
