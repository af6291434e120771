// Same answer under every BLAS: this test runs its own probe (below) under reference BLAS and
// OpenBLAS's Prescott and Haswell kernels (tools/with_blas.sh) and compares digests of every bit
// the probe computes. With our LDL^T nothing of a solve depends on the BLAS (its kernels are
// ours, and Ipopt's level-1 BLAS is replaced: solver/ipopt_blas.cpp).
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include <gtest/gtest.h>
#include <unistd.h>

#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/examples/planning_scenes.h"
#include "fesd_trajopt/examples/push_t.h"
#include "fesd_trajopt/planning/accuracy_ladder.h"
#include "fesd_trajopt/planning/closed_loop.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/scene_units.h"
#include "fesd_trajopt/solver/lpec.h"
#include "support/corner_mpcc.h"
#include "support/hard_cases.h"
#include "support/scene_tasks.h"

namespace {

constexpr const char* kProbeVariable = "FESD_BLAS_PROBE";

/// FNV-1a over the bytes of every number added.
class Digest {
 public:
  void add(double value) { addBytes(&value, sizeof value); }
  void add(const Eigen::MatrixXd& values) {
    for (Eigen::Index i = 0; i < values.size(); ++i) add(values.data()[i]);
  }
  void add(const fesd::Trajectory& trajectory) {
    for (double t : trajectory.times) add(t);
    for (const Eigen::VectorXd& x : trajectory.states) add(x);
    for (const Eigen::VectorXd& u : trajectory.controls) add(u);
    for (const fesd::ElementValues& element : trajectory.elements) {
      add(element.stage_states);
      add(element.stage_multipliers);
    }
    for (const fesd::SwitchEvent& event : trajectory.switches) add(event.time);
  }
  std::uint64_t value() const { return hash_; }

 private:
  void addBytes(const void* data, size_t size) {
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < size; ++i) hash_ = (hash_ ^ bytes[i]) * 1099511628211ull;
  }
  std::uint64_t hash_ = 14695981039346656037ull;
};

/// min (x-1)^2 + (y+1)^2, 0 <= x _|_ y >= 0, its branch x = 0 fixed at the origin: an LPEC with a
/// binary (Cbc and Clp), whose minimiser leaves the branch.
double lpecValueAtACorner() {
  fesd_test::CornerMpcc<> corner(-1.0);
  corner.nlp.finalize();
  fesd::NlpAssembly& nlp = corner.nlp;
  const std::vector<double> origin = {0.0, 0.0};
  nlp.fixGivenActiveSet({true}, origin.data());
  const fesd::LpecResult result = fesd::Lpec(nlp, origin, {}, 1e-6).solve(1e-3);
  EXPECT_TRUE(result.solved && result.other_branch) << result.message;
  return result.value;
}

/// Hard cases through Ipopt at every step (no active-set Newton), the showcase scene up the
/// accuracy ladder with its verifications, a push executed with feedback, the showcase by the
/// active-set method with its LPECs, the showcase at desk size, and a turning box pushed into a
/// corner, all with our LDL^T.
std::uint64_t probeDigest() {
  Digest digest;
  fesd::SimulationOptions options = hard_cases::fesdOptions(2, 2);
  options.active_set_steps = false;
  const Eigen::Vector2d corner_start(2.0, 1.0);
  fesd::FesdIntegrator corner(hard_cases::cornerScene(corner_start).model(), options);
  const fesd::SimulationResult slide =
      corner.simulate(corner_start, 2.9, 4, {hard_cases::kCornerVelocity});
  digest.add(slide.trajectory);
  digest.add(slide.totals.iterations);
  const hard_cases::DiscRelease small{1e-3, 1e-3};
  fesd::FesdIntegrator disc(small.model(), options);
  const fesd::SimulationResult release =
      disc.simulate(small.start(), small.horizon(), 14, {small.velocity()});
  digest.add(release.trajectory);
  digest.add(release.totals.iterations);
  // The showcase up an accuracy ladder: a rung refined from the plan before, each verified
  // interval by interval (with sensitivities: the open-loop gain) and open loop.
  fesd::SceneSolveOptions ladder;
  ladder.ocp.discretization.num_elements = 3;
  ladder.verification.num_stages = 3;
  ladder.verification.num_elements = 6;
  const fesd::SceneOutcome showcase =
      fesd::solveToAccuracy(fesd::manipulation_example::task(30), fesd::TaskLimits{}, ladder, 1e-6);
  EXPECT_EQ(showcase.status, fesd::SolveStatus::kSuccess) << showcase.message;
  EXPECT_GE(showcase.refinements.size(), 2u);
  digest.add(showcase.trajectory);
  digest.add(showcase.report.iterations);
  for (double error : showcase.verification.interval_errors) digest.add(error);
  digest.add(showcase.verification.open_loop_error);
  digest.add(showcase.verification.open_loop_gain);
  digest.add(showcase.verification.open_loop);
  // A push executed with feedback: replans warm from the rest of the plan before.
  fesd::SceneTask push = fesd_test::pushAlongX();
  push.bodies[1].target = Eigen::Vector2d(3.0, 1.0);
  push.num_intervals = 8;
  fesd::ClosedLoopOptions loop;
  loop.first_accuracy = 0.0;
  loop.replan_every = 2;
  const fesd::ClosedLoopRun run = fesd::executeWithFeedback(push, fesd::TaskLimits{}, loop);
  EXPECT_EQ(run.status, fesd::SolveStatus::kSuccess) << run.message;
  digest.add(run.executed);
  for (const fesd::Replan& replan : run.replans) digest.add(replan.iterations);
  fesd::SceneSolveOptions active_set;
  active_set.ocp.discretization.num_elements = 3;
  active_set.ocp.homotopy.method = fesd::MpccMethod::kActiveSet;
  const fesd::SceneOutcome certified =
      fesd::solveSceneTask(fesd::manipulation_example::task(30), fesd::TaskLimits{}, active_set);
  EXPECT_TRUE(certified.report.certified) << certified.message;
  digest.add(certified.trajectory);
  digest.add(certified.report.iterations);
  digest.add(certified.report.lpec_value);
  digest.add(lpecValueAtACorner());
  // A first relaxation at Ipopt's limit started over looser (every NLP capped at 1 iteration).
  fesd_test::CornerMpcc<> capped_corner;
  fesd::HomotopyOptions capped;
  capped.ipopt.max_iterations = 1;
  capped.loosen_failed_first_relaxation = true;
  const fesd::MpccReport loosened = capped_corner.solve(capped);
  for (double value : loosened.solution) digest.add(value);
  for (const fesd::HomotopyStep& step : loosened.history) digest.add(step.objective);
  // A replan's early polish kept although its branch check did not solve (1 iteration).
  const fesd::MpccReport kept = fesd_test::OnlyTheOrigin().solveWithAnUnsolvedBranchCheck(true);
  for (double value : kept.solution) digest.add(value);
  digest.add(kept.iterations);
  // A homotopy resumed from a polish of the plan's active set that stopped unsolved.
  fesd_test::CornerMpcc<> cut_corner;
  const fesd::MpccReport resumed = fesd_test::solveCutCornerAfterAnUnsolvedPolish(cut_corner, true);
  for (double value : resumed.solution) digest.add(value);
  digest.add(resumed.iterations);
  // The showcase at desk size (a 2 cm pusher): solved in units of its length scale, answered in
  // metres.
  const fesd::SceneOutcome desk = fesd::solveSceneTask(
      fesd::scaledTask(fesd::manipulation_example::task(30), 0.01), fesd::TaskLimits{}, ladder);
  EXPECT_EQ(desk.status, fesd::SolveStatus::kSuccess) << desk.message;
  digest.add(desk.trajectory);
  digest.add(desk.report.objective);
  // A box that turns, pushed into a corner (pair model of turning spheres, the bounding-disc
  // guess), verified.
  fesd::SceneSolveOptions turning = fesd_test::nodeGridOptions();
  turning.verify = true;
  const fesd::SceneOutcome box =
      fesd::solveSceneTask(fesd_test::boxIntoACorner(), fesd::TaskLimits{}, turning);
  EXPECT_EQ(box.status, fesd::SolveStatus::kSuccess) << box.message;
  digest.add(box.trajectory);
  digest.add(box.report.iterations);
  digest.add(box.verification.error);
  // Push-T from a start the turning push plan brings into one round.
  const fesd::SceneOutcome push_t =
      fesd::solveSceneTask(fesd::push_t::randomStart(0), fesd::TaskLimits{}, turning);
  EXPECT_EQ(push_t.status, fesd::SolveStatus::kSuccess) << push_t.message;
  digest.add(push_t.trajectory);
  digest.add(push_t.report.iterations);
  digest.add(push_t.verification.error);
  // The same with the NLP's functions evaluated on two threads (copies of the turning body's
  // pair functions beside the originals): the same bits.
  fesd::SceneSolveOptions two_threads = turning;
  two_threads.ocp.discretization.evaluation_threads = fesd::NlpAssembly::Threads::kTwo;
  const fesd::SceneOutcome push_t_two =
      fesd::solveSceneTask(fesd::push_t::randomStart(0), fesd::TaskLimits{}, two_threads);
  Digest one_thread, two_thread;
  one_thread.add(push_t.trajectory);
  two_thread.add(push_t_two.trajectory);
  EXPECT_EQ(one_thread.value(), two_thread.value());
  EXPECT_EQ(push_t_two.report.iterations, push_t.report.iterations);
  digest.add(push_t_two.trajectory);
  // A lazy round started cold from a plan through its new pairs (the session's second Ipopt
  // application, its barrier bounded).
  const fesd::SceneOutcome posts = fesd::solveSceneTask(
      fesd::planning_scenes::postsScene(2).task, fesd::TaskLimits{}, fesd_test::nodeGridOptions());
  EXPECT_EQ(posts.status, fesd::SolveStatus::kSuccess) << posts.message;
  EXPECT_EQ(posts.pair_rounds, 2) << posts.message;
  digest.add(posts.trajectory);
  digest.add(posts.report.iterations);
  return digest.value();
}

TEST(BlasIndependenceProbe, PrintsTheDigest) {
  if (std::getenv(kProbeVariable) == nullptr) GTEST_SKIP() << "run by BlasIndependence";
  std::printf("digest=%016llx\n", static_cast<unsigned long long>(probeDigest()));
}

/// The probe's digest in a child process under `variant`; "" if it printed none.
std::string digestUnder(const std::string& variant) {
  char self[4096] = {};
  if (readlink("/proc/self/exe", self, sizeof self - 1) <= 0) return "";
  const std::string command = std::string(kProbeVariable) +
                              "=1 " FESD_SOURCE_DIR "/tools/with_blas.sh " + variant + " " + self +
                              " --gtest_filter=BlasIndependenceProbe.* 2>&1";
  FILE* child = popen(command.c_str(), "r");
  if (child == nullptr) return "";
  std::string digest;
  char line[4096];
  while (std::fgets(line, sizeof line, child) != nullptr) {
    if (std::strncmp(line, "digest=", 7) == 0) digest = std::string(line + 7, 16);
  }
  return pclose(child) == 0 ? digest : "";
}

TEST(BlasIndependence, OurSolvesAreTheSameBitForBitUnderEveryKernel) {
  const std::string reference = digestUnder("reference");
  ASSERT_EQ(reference.size(), 16u) << "the probe failed under reference BLAS";
  for (const char* variant : {"openblas-prescott", "openblas-haswell"}) {
    EXPECT_EQ(digestUnder(variant), reference) << variant;
  }
  hard_cases::recordNumber("digest_low_bits", std::strtoull(reference.c_str() + 8, nullptr, 16));
}

}  // namespace
