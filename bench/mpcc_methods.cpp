// mpcc-methods: the homotopy and the active-set method (MpccMethod) side by side on the node's
// default request (verified, the accuracy ladder, lazy pairs) of the default scene, the
// planning-sweep families and the shipped robots: status, iterations by kind of NLP, LPECs,
// time, objective, certificate. CSV, then a summary per method.
#include <algorithm>
#include <cstdio>
#include <map>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_scenes.h"
#include "commands.h"
#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/examples/planning_scenes.h"
#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd_bench {
namespace {

struct Case {
  std::string name;
  fesd::SceneTask task;
};

struct Totals {
  int cases = 0, successes = 0, certified = 0;
  std::vector<double> iterations;
};

}  // namespace

int mpccMethods(const Arguments& args) {
  namespace ps = fesd::planning_scenes;
  const std::vector<std::string> families = args.texts("families", ps::families());
  const int first_seed = args.integer("first-seed", 0);
  const int scenes = args.integer("scenes", 12);
  const std::vector<std::string> robots = args.texts("robots", {"planar_arm", "panda"});
  const double budget = args.number("budget", 120.0);
  const double accuracy = args.number("accuracy", 1e-2);
  const std::vector<std::string> method_names = args.texts("methods", {"homotopy", "active_set"});
  args.rejectUnused();

  std::vector<Case> cases = {{"default", fesd::manipulation_example::task(40)}};
  for (const std::string& family : families) {
    for (int seed = first_seed; seed < first_seed + scenes; ++seed) {
      cases.push_back({family + "_" + std::to_string(seed), ps::scene(family, seed).task});
    }
  }
  for (const std::string& robot : robots) {
    if (robot == "planar_arm") {
      cases.push_back({robot, fesd::planarArmPushTask(shippedRobot("planar_arm.urdf"))});
    } else if (robot == "panda") {
      fesd::SceneTask panda = fesd::pandaPushTask(shippedRobot("panda_spherized.urdf"));
      panda.num_intervals = 20;
      panda.horizon = 4.0;
      cases.push_back({"panda_20", panda});
    } else {
      throw std::invalid_argument("--robots=planar_arm,panda");
    }
  }
  std::printf(
      "case,method,status,wall_s,ipopt_iterations,relaxed_nlps,branch_nlps,lpecs,lpec_s,"
      "objective,certified,lpec_value,verification_error\n");
  std::map<std::string, Totals> totals;
  for (const Case& c : cases) {
    for (const std::string& name : method_names) {
      fesd::SceneSolveOptions options = nodeDefaultOptions(budget);
      if (!fesd::parseMethod(name, options.ocp.homotopy.method)) {
        throw std::invalid_argument("--methods=homotopy,active_set");
      }
      fesd::Stopwatch stopwatch;
      const fesd::SceneOutcome outcome =
          fesd::solveToAccuracy(c.task, fesd::TaskLimits{}, options, accuracy);
      const double seconds = stopwatch.wallSeconds();
      const fesd::MpccReport& report = outcome.report;
      const bool success = outcome.solved() && outcome.status == fesd::SolveStatus::kSuccess;
      Totals& t = totals[name];
      ++t.cases;
      t.successes += success;
      t.certified += success && report.certified;
      t.iterations.push_back(report.iterations);
      std::printf("%s,%s,%s,%.3f,%d,%d,%d,%d,%.3f,%.10g,%d,%.3g,%.3g\n", c.name.c_str(),
                  name.c_str(),
                  outcome.solved() ? fesd::statusName(outcome.status).c_str() : "refused", seconds,
                  report.iterations, report.relaxedNlps(), report.branch_nlps, report.lpecs,
                  report.lpec_seconds, report.objective, report.certified, report.lpec_value,
                  outcome.verification.error);
      std::fflush(stdout);
    }
  }
  for (const auto& [name, t] : totals) {
    std::printf(
        "# %s: %d of %d SUCCESS (%d certified); Ipopt iterations median %.1f, largest %.0f\n",
        name.c_str(), t.successes, t.cases, t.certified, median(t.iterations),
        t.iterations.empty() ? 0 : *std::max_element(t.iterations.begin(), t.iterations.end()));
  }
  return 0;
}

}  // namespace fesd_bench
