#include "showcase_reference.h"

#include <algorithm>
#include <cstdio>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd_bench {

double timeShowcase(const fesd::SceneSolveOptions& options, const char* prefix) {
  fesd::Stopwatch stopwatch;
  const fesd::SceneOutcome showcase =
      fesd::solveSceneTask(fesd::manipulation_example::task(40), fesd::TaskLimits{}, options);
  const double seconds = stopwatch.wallSeconds();
  std::printf("%sshowcase: %s, %d Ipopt iterations (%.3f ms each), objective %.6g, %.3f s\n",
              prefix, fesd::statusName(showcase.status).c_str(), showcase.report.iterations,
              1e3 * (showcase.report.ipopt_seconds + showcase.report.evaluation_seconds) /
                  std::max(1, showcase.report.iterations),
              showcase.report.objective, seconds);
  return seconds;
}

}  // namespace fesd_bench
