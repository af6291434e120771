// push-t: the Push-T benchmark in our units (examples/push_t.h) through the node's default
// request: per random start the status, seconds (and their ratio to the default scene's in the
// same run), iterations, the T's position and yaw errors and the verification error; CSV, then a
// summary. --trajectory=PATH also writes one start's plan (--trajectory-seed, by default the
// first; tools/plot_benchmarks.py draws it).
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_scenes.h"
#include "commands.h"
#include "fesd_trajopt/examples/push_t.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd_bench {
namespace {

/// The plan of one start: the T's spheres (in its frame) and target as comments, then per
/// element boundary the time, the pusher's position and the T's position and yaw.
void writeTrajectory(const std::string& path, const fesd::SceneTask& task,
                     const fesd::SceneOutcome& outcome) {
  std::FILE* file = std::fopen(path.c_str(), "w");
  if (!file) {
    std::fprintf(stderr, "push-t: cannot write %s\n", path.c_str());
    return;
  }
  const fesd::Scene& scene = task.scene;
  std::fprintf(file, "# pusher_radius,%.17g\n", scene.bodies()[0].radius);
  for (const fesd::FreeBodySphere& sphere : scene.bodies()[1].spheres) {
    std::fprintf(file, "# sphere,%.17g,%.17g,%.17g\n", sphere.offset.x(), sphere.offset.y(),
                 sphere.radius);
  }
  std::fprintf(file, "# target,%.17g,%.17g,%.17g\n", task.bodies[1].target.x(),
               task.bodies[1].target.y(), task.bodies[1].target_yaw);
  std::fprintf(file, "# status,%s\n", fesd::statusName(outcome.status).c_str());
  std::fprintf(file, "t,pusher_x,pusher_y,t_x,t_y,yaw\n");
  const fesd::Trajectory& trajectory = outcome.trajectory;
  for (size_t i = 0; i < trajectory.states.size(); ++i) {
    const Eigen::VectorXd& x = trajectory.states[i];
    const Eigen::VectorXd pusher = scene.position(0, x), t = scene.position(1, x);
    std::fprintf(file, "%.6f,%.9g,%.9g,%.9g,%.9g,%.9g\n", trajectory.times[i], pusher.x(),
                 pusher.y(), t.x(), t.y(), scene.yaw(1, x));
  }
  std::fclose(file);
}

}  // namespace

int pushT(const Arguments& args) {
  const int first_seed = args.integer("first-seed", 0);
  const int starts = args.integer("starts", 16);
  fesd::SceneSolveOptions options = nodeDefaultOptions(args.number("budget", 60.0));
  applyHomotopyArguments(args, options.ocp.homotopy);
  applySceneArguments(args, options);
  const double accuracy = args.number("accuracy", 1e-2);
  const std::string trajectory = args.text("trajectory", "");
  const int trajectory_seed = args.integer("trajectory-seed", first_seed);
  args.rejectUnused();
  if (!trajectory.empty() &&
      (trajectory_seed < first_seed || trajectory_seed >= first_seed + starts)) {
    std::fprintf(stderr, "push-t: --trajectory-seed=%d is not among the starts %d..%d\n",
                 trajectory_seed, first_seed, first_seed + starts - 1);
    return 2;
  }
  const double default_seconds = timeDefaultScene(options, accuracy);
  std::printf(
      "seed,status,wall_s,ratio,ipopt_iterations,start_yaw_deg,turn_deg,position_error,"
      "yaw_error_deg,verification_error\n");
  std::vector<double> walls;
  int successes = 0;
  for (int seed = first_seed; seed < first_seed + starts; ++seed) {
    const fesd::SceneTask task = fesd::push_t::randomStart(seed);
    fesd::Stopwatch stopwatch;
    const fesd::SceneOutcome outcome =
        fesd::solveToAccuracy(task, fesd::TaskLimits{}, options, accuracy);
    const double seconds = stopwatch.wallSeconds();
    if (!trajectory.empty() && seed == trajectory_seed) writeTrajectory(trajectory, task, outcome);
    walls.push_back(seconds);
    successes += outcome.status == fesd::SolveStatus::kSuccess;
    const Eigen::VectorXd end = outcome.trajectory.finalState();
    const double degrees = 180.0 / M_PI;
    const double start_yaw = task.scene.bodies()[1].yaw;
    std::printf("%d,%s,%.3f,%.1f,%d,%.1f,%.1f,%.3g,%.3g,%.3g\n", seed,
                fesd::statusName(outcome.status).c_str(), seconds, seconds / default_seconds,
                outcome.report.iterations, start_yaw * degrees,
                (task.bodies[1].target_yaw - start_yaw) * degrees,
                (task.scene.position(1, end) - task.bodies[1].target).norm(),
                std::fabs(task.scene.yaw(1, end) - task.bodies[1].target_yaw) * degrees,
                outcome.verification.error);
    std::fflush(stdout);
  }
  const double middle = median(walls);
  double slowest = 0.0;
  for (double wall : walls) slowest = std::max(slowest, wall);
  std::printf(
      "# %d starts: %d SUCCESS; wall time median %.3f s, slowest %.3f s (%.1fx and %.1fx the "
      "default scene's)\n",
      starts, successes, middle, slowest, middle / default_seconds, slowest / default_seconds);
  return 0;
}

}  // namespace fesd_bench
