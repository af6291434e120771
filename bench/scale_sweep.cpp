// scale-sweep: the default scene with every length multiplied by k (radii, positions, targets,
// workspace and speed bounds; the horizon, the intervals and the weights kept: the same motion
// scaled, its objective k^2 times) through the node's default request: status, Ipopt iterations,
// wall time and its ratio to k = 1's, the first contact, objective / k^2 and the plan's largest
// deviation from k = 1's plan scaled; CSV, then a summary.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <vector>

#include "bench_args.h"
#include "bench_scenes.h"
#include "commands.h"
#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/scene/scene_units.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd_bench {
namespace {

double firstContact(const fesd::Trajectory& trajectory) {
  for (const fesd::SwitchEvent& event : trajectory.switches) {
    if (event.kind == fesd::SwitchEvent::Kind::kContact) return event.time;
  }
  return std::numeric_limits<double>::quiet_NaN();
}

/// The largest difference of the states at the element boundaries, scaled back by k, from the
/// reference's (NaN on other grids).
double deviation(const fesd::SceneOutcome& outcome, const fesd::SceneOutcome& reference, double k) {
  const std::vector<Eigen::VectorXd>& states = outcome.trajectory.states;
  if (states.size() != reference.trajectory.states.size()) {
    return std::numeric_limits<double>::quiet_NaN();
  }
  double largest = 0.0;
  for (size_t i = 0; i < states.size(); ++i) {
    largest =
        std::max(largest, (states[i] / k - reference.trajectory.states[i]).cwiseAbs().maxCoeff());
  }
  return largest;
}

}  // namespace

int scaleSweep(const Arguments& args) {
  const std::vector<double> default_factors{0.003, 0.01, 0.03, 0.1, 0.25, 1.0, 4.0, 10.0, 100.0};
  std::vector<double> factors;
  for (const std::string& text : args.texts("factors", {})) factors.push_back(std::stod(text));
  if (factors.empty()) factors = default_factors;
  fesd::SceneSolveOptions options = nodeDefaultOptions(args.number("budget", 120.0));
  applyHomotopyArguments(args, options.ocp.homotopy);
  applySceneArguments(args, options);
  const double accuracy = args.number("accuracy", 1e-2);
  args.rejectUnused();
  const fesd::SceneTask showcase = fesd::manipulation_example::task(40);
  // The reference (k = 1) first, twice: the first run pays for what a node pays once.
  fesd::SceneOutcome reference;
  double reference_seconds = 0.0;
  for (int run = 0; run < 2; ++run) {
    fesd::Stopwatch stopwatch;
    reference = fesd::solveToAccuracy(showcase, fesd::TaskLimits{}, options, accuracy);
    reference_seconds = stopwatch.wallSeconds();
  }
  std::printf(
      "k,status,ipopt_iterations,wall_s,ratio,first_contact,objective_over_k2,objective_change,"
      "state_deviation,length_scale,verification_error\n");
  int successes = 0, same_iterations = 0;
  double worst_contact = 0.0, worst_objective = 0.0;
  for (const double k : factors) {
    const fesd::SceneTask task = fesd::scaledTask(showcase, k);
    fesd::Stopwatch stopwatch;
    const fesd::SceneOutcome outcome =
        fesd::solveToAccuracy(task, fesd::TaskLimits{}, options, accuracy);
    const double seconds = stopwatch.wallSeconds();
    const double objective = outcome.report.objective / (k * k);
    const double change = std::fabs(objective / reference.report.objective - 1.0);
    const double contact = firstContact(outcome.trajectory);
    successes += outcome.status == fesd::SolveStatus::kSuccess;
    same_iterations += outcome.report.iterations == reference.report.iterations;
    worst_contact =
        std::max(worst_contact, std::isnan(contact)
                                    ? std::numeric_limits<double>::infinity()
                                    : std::fabs(contact - firstContact(reference.trajectory)));
    worst_objective = std::max(worst_objective, change);
    std::printf("%g,%s,%d,%.3f,%.2f,%.6f,%.10g,%.2g,%.2g,%.4g,%.3g\n", k,
                fesd::statusName(outcome.status).c_str(), outcome.report.iterations, seconds,
                seconds / reference_seconds, contact, objective, change,
                deviation(outcome, reference, k), outcome.length_scale, outcome.verification.error);
    std::fflush(stdout);
  }
  std::printf(
      "# %zu factors: %d SUCCESS, %d with k = 1's %d Ipopt iterations; first contact within %.2g s "
      "of k = 1's, objective / k^2 within %.2g relative (k = 1: %.3f s)\n",
      factors.size(), successes, same_iterations, reference.report.iterations, worst_contact,
      worst_objective, reference_seconds);
  return 0;
}

}  // namespace fesd_bench
