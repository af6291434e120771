#include "bench_scenes.h"

#include <cstdio>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

#include "bench_args.h"
#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd_bench {

fesd::SceneTask showcaseWithRocks(int intervals, int rocks) {
  fesd::SceneTask task = fesd::manipulation_example::task(intervals);
  for (int i = 0; i < rocks; ++i) {
    task.scene.bodies().push_back(
        {"rock_" + std::to_string(i), 1.0, Eigen::Vector2d(-12.0 + 4.0 * i, -12.0), false});
    task.bodies.push_back(fesd::BodyTask{});
  }
  return task;
}

fesd::SceneSolveOptions nodeDefaultOptions(double budget) {
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements = 3;
  options.ocp.discretization.num_stages = 2;
  options.ocp.homotopy.wall_time_budget = budget;
  options.lazy_pairs = true;
  options.pair_margin = 0.1;
  options.verify = true;
  options.verification.num_stages = 3;
  options.verification.num_elements = 6;
  return options;
}

void applySceneArguments(const Arguments& args, fesd::SceneSolveOptions& options) {
  options.length_scaling = args.flag("length-scaling", options.length_scaling);
  const std::string threads = args.text("evaluation-threads", "measured");
  using Threads = fesd::NlpAssembly::Threads;
  if (threads == "one" || threads == "two" || threads == "measured") {
    options.ocp.discretization.evaluation_threads = threads == "one"   ? Threads::kOne
                                                    : threads == "two" ? Threads::kTwo
                                                                       : Threads::kMeasured;
  } else {
    throw std::invalid_argument("--evaluation-threads=measured|one|two");
  }
}

double timeDefaultScene(const fesd::SceneSolveOptions& options, double accuracy) {
  fesd::SceneOutcome reference;
  std::vector<double> runs;
  for (int run = 0; run < 3; ++run) {
    fesd::Stopwatch time;
    reference = fesd::solveToAccuracy(fesd::manipulation_example::task(40), fesd::TaskLimits{},
                                      options, accuracy);
    runs.push_back(time.wallSeconds());
  }
  const double seconds = median({runs[1], runs[2]});
  std::printf(
      "# default scene, node default request: %s, %d Ipopt iterations, %.3f s (first run %.3f s), "
      "verification error %.3g, open loop %.3g, gain %.3g\n",
      fesd::statusName(reference.status).c_str(), reference.report.iterations, seconds, runs[0],
      reference.verification.error, reference.verification.open_loop_error,
      reference.verification.open_loop_gain);
  return seconds;
}

std::shared_ptr<const fesd::KinematicModel> shippedRobot(const std::string& file) {
  std::ifstream stream(std::string(FESD_ROBOTS_DIR) + "/" + file);
  std::stringstream text;
  text << stream.rdbuf();
  const fesd::KinematicModelResult built = fesd::buildKinematicModel(text.str());
  if (!built.error.empty()) throw std::runtime_error(file + ": " + built.error);
  return std::make_shared<const fesd::KinematicModel>(built.model);
}

}  // namespace fesd_bench
