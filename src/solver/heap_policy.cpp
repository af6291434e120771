#include "fesd_trajopt/solver/heap_policy.h"

#include <malloc.h>

namespace fesd {

void keepLargeAllocationsInTheHeap() {
  constexpr int kLargest = 1 << 30;  // bytes: factors and fronts stay below it
  mallopt(M_MMAP_THRESHOLD, kLargest);
  mallopt(M_TRIM_THRESHOLD, kLargest);
}

void releaseFreeMemory(std::size_t keep_bytes) {
  if (mallinfo2().fordblks > keep_bytes) malloc_trim(0);
}

}  // namespace fesd
