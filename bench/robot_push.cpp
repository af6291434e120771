// robot-push: a shipped robot push (examples/robot_scenes.h) solved as solveSceneTask solves it,
// after the showcase in the same process for the time ratio: status, wall time, Ipopt iterations
// per homotopy step, pairs in reach / modelled / checked / rounds, the NLP's size, the puck's
// distance from its target, the smallest gaps at the element boundaries (every pair in reach)
// and in the re-simulation, and the contact and release times per modelled pair.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_args.h"
#include "bench_scenes.h"
#include "commands.h"
#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/solver/kkt_capture.h"
#include "fesd_trajopt/solver/stopwatch.h"
#include "showcase_reference.h"

namespace fesd_bench {

int robotPush(const Arguments& args) {
  const std::string robot = args.text("robot", "panda");
  const std::string pushed = args.text("pushed", "puck");
  if (pushed != "puck" && !(pushed == "bar" && robot == "panda")) {
    throw std::invalid_argument("--pushed=puck|bar (a bar for the Panda)");
  }
  fesd::SceneTask task =
      robot == "panda"
          ? (pushed == "bar" ? fesd::pandaBarTask(shippedRobot("panda_spherized.urdf"))
                             : fesd::pandaPushTask(shippedRobot("panda_spherized.urdf")))
      : robot == "planar_arm" ? fesd::planarArmPushTask(shippedRobot("planar_arm.urdf"))
      : robot == "ur3e"       ? fesd::ur3ePushTask(shippedRobot("ur3e_spherized.urdf"))
      : robot == "planar_iiwa"
          ? fesd::planarIiwaPushTask(shippedRobot("planar_iiwa.urdf"))
          : throw std::invalid_argument("--robot=panda|planar_arm|ur3e|planar_iiwa");
  task.num_intervals = args.integer("intervals", task.num_intervals);
  task.horizon = args.number("horizon", task.horizon);
  fesd::SceneSolveOptions options;
  options.ocp.discretization.num_elements =
      args.integer("elements", options.ocp.discretization.num_elements);
  options.ocp.discretization.num_stages =
      args.integer("stages", options.ocp.discretization.num_stages);
  options.ocp.homotopy.wall_time_budget = args.number("budget", 150.0);
  const std::string pairs = args.text("pairs", "lazy");
  options.lazy_pairs = pairs == "lazy";
  options.pair_margin = args.number("margin", options.pair_margin);
  options.verify = args.flag("verify", true);
  applyHomotopyArguments(args, options.ocp.homotopy);
  applySceneArguments(args, options);
  const bool with_showcase = args.flag("showcase", true);
  // > 0: the node's default request (the accuracy ladder to this target, in units of the
  // scene's length scale; of the task's own with --length-scaling=false).
  const double accuracy = args.number("accuracy", 0.0);
  args.rejectUnused();
  if (pairs != "lazy" && pairs != "all") throw std::invalid_argument("--pairs=lazy|all");

  // Timed as planning-sweep times it: the node's scene solve with 3 elements and 2 stages.
  fesd::SceneSolveOptions showcase_options;
  showcase_options.ocp.discretization.num_elements = 3;
  showcase_options.ocp.discretization.num_stages = 2;
  const double showcase_seconds = with_showcase ? timeShowcase(showcase_options, "") : 0.0;

  fesd::Stopwatch stopwatch;
  fesd::KktCapture capture;
  const fesd::SceneOutcome outcome =
      accuracy > 0.0 ? fesd::solveToAccuracy(task, fesd::TaskLimits{}, options, accuracy)
                     : fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  const double seconds = stopwatch.wallSeconds();
  const fesd::KktCapture::Totals kkt = capture.totals();
  if (!outcome.invalid.empty()) {
    std::printf("refused: %s\n", outcome.invalid.c_str());
    return 1;
  }
  const fesd::Scene& scene = task.scene;
  std::vector<fesd::ContactPair> in_reach;
  int checked = 0;
  for (const fesd::PairDecision& decision : outcome.decisions) {
    if (decision.modelled || decision.checked) in_reach.push_back(decision.pair);
    checked += decision.checked;
  }
  const fesd::OcpDefinition ocp = fesd::buildOcp(task, outcome.modelled);
  const fesd::OcpSolver last_round(ocp, options.ocp);
  const fesd::NlpAssembly& nlp = last_round.discretization().nlp();
  std::printf("%s push (%s pairs, %d intervals x %d elements x %d stages, T = %g s): %s in %.2f s",
              robot.c_str(), pairs.c_str(), task.num_intervals,
              options.ocp.discretization.num_elements, options.ocp.discretization.num_stages,
              task.horizon, fesd::statusName(outcome.status).c_str(), seconds);
  if (showcase_seconds > 0.0) std::printf(" = %.1fx the showcase", seconds / showcase_seconds);
  std::printf(
      "\n  %d Ipopt iterations (%.3f ms each; Ipopt %.2f s, evaluations %.2f s; the rest is the "
      "guess, pair checks and verification), objective %.6g\n",
      outcome.report.iterations,
      1e3 * (outcome.report.ipopt_seconds + outcome.report.evaluation_seconds) /
          std::max(1, outcome.report.iterations),
      outcome.report.ipopt_seconds, outcome.report.evaluation_seconds, outcome.report.objective);
  if (kkt.factorisations > 0) {
    std::printf(
        "  KKT (our LDL^T): %d factorisations (%.2f per iteration) in %.2f s, %d solves in %.2f s, "
        "largest system %d with %lld factor entries\n",
        kkt.factorisations,
        static_cast<double>(kkt.factorisations) / std::max(1, outcome.report.iterations),
        kkt.factor_seconds, kkt.solves, kkt.solve_seconds, kkt.largest_dimension,
        kkt.factor_entries);
  }
  std::printf("  last NLP: %d variables, %d constraints, %d complementarities\n",
              nlp.numVariables(), nlp.numConstraints(), nlp.numComplementarities());
  std::printf("  first guess: residual %.3g in the NLP's equations\n", outcome.guess_residual);
  std::printf("  pairs: %zu in reach, %zu modelled, %d checked, %d rounds; pusher %s\n",
              in_reach.size(), outcome.modelled.size(), checked, outcome.pair_rounds,
              outcome.pusher_sphere >= 0 ? scene.robot().spheres[outcome.pusher_sphere].name.c_str()
                                         : "none");
  std::printf("  homotopy steps (sigma: iterations, Ipopt status, s):");
  for (const fesd::HomotopyStep& step : outcome.report.history) {
    std::printf(" %.1e:%d:%s:%.2f", step.sigma, step.iterations, step.ipopt_status.c_str(),
                step.wall_seconds);
  }
  std::printf("\n");
  if (outcome.trajectory.states.empty()) return 1;
  std::printf(
      "  target distance %.2e; smallest gap at the element boundaries %.2e (every pair in reach), "
      "in the re-simulation %.2e; verification error %.2e, open loop %.3g, %.3f s (%.2fx the "
      "solve's Ipopt and evaluations)\n",
      outcome.target_distances[0], fesd::smallestBoundaryGap(scene, in_reach, outcome.trajectory),
      outcome.verification.gap, outcome.verification.error, outcome.verification.open_loop_error,
      outcome.verification.seconds,
      outcome.verification.seconds /
          std::max(1e-9, outcome.report.ipopt_seconds + outcome.report.evaluation_seconds));
  // Enough digits to compare plans across BLAS builds (tools/with_blas.sh).
  const Eigen::VectorXd end = outcome.trajectory.finalState();
  std::printf("  objective %.12g; end state", outcome.report.objective);
  for (int i = 0; i < end.size(); ++i) std::printf(" %.9f", end(i));
  std::printf("\n");
  for (const fesd::SwitchEvent& event : outcome.trajectory.switches) {
    std::printf("  %s of %s at t = %.4f\n", fesd::SwitchEvent::kindName(event.kind).c_str(),
                scene.pairName(outcome.modelled[event.constraint]).c_str(), event.time);
  }
  return outcome.status == fesd::SolveStatus::kSuccess ? 0 : 1;
}

}  // namespace fesd_bench
