#include <gtest/gtest.h>

#include "fesd_trajopt/solver/heap_policy.h"

int main(int argc, char** argv) {
  fesd::keepLargeAllocationsInTheHeap();
  ::testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
