// The memory estimate of an NLP's solve (solver/memory_estimate.cpp).
#include <gtest/gtest.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/solver/memory_estimate.h"

namespace {

double showcaseMib(int intervals, int elements) {
  fesd::OcpOptions options;
  options.discretization.num_elements = elements;
  const fesd::OcpSolver solver(fesd::manipulation_example::ocp(intervals), options);
  return fesd::estimatedSolverMib(solver.discretization().nlp(), intervals * elements);
}

TEST(MemoryEstimate, GrowsLinearlyWithTheGridAndStaysSmallForTheShowcase) {
  const double showcase = showcaseMib(40, 3);
  EXPECT_GT(showcase, 0.5);  // measured: the node peaks at 34 MiB, 25 of them at rest
  EXPECT_LT(showcase, 10.0);
  // Twice the intervals: twice the rows and twice the elements, so twice the memory.
  EXPECT_NEAR(showcaseMib(80, 3) / showcase, 2.0, 0.1);
}

}  // namespace
