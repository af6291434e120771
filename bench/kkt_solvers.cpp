// kkt-solvers: our multifrontal LDL^T against MUMPS on the KKT systems of real solves. Per scene,
// the whole solve under each linear solver (status, Ipopt iterations, objective, wall time), then
// the first KKT matrices Ipopt factorised replayed through both: analysis, time per factorisation
// and per solve (median of repeats), fill and flops, and whether the inertias agree.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <dmumps_c.h>

#include "bench_args.h"
#include "bench_scenes.h"
#include "commands.h"
#include "fesd_trajopt/examples/robot_scenes.h"
#include "fesd_trajopt/linalg/kkt_ordering.h"
#include "fesd_trajopt/linalg/multifrontal_ldlt.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/solver/kkt_capture.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd_bench {
namespace {

struct SolveFigures {
  std::string status;
  int iterations = 0;
  double objective = 0.0, seconds = 0.0;
};

/// One KKT matrix factorised and solved by MUMPS as Ipopt 3.11.9 drives it (symmetric
/// indefinite, the options ipopt_session sets), with the analysis done once.
class MumpsReplay {
 public:
  explicit MumpsReplay(const fesd::linalg::LowerPattern& pattern) {
    id_.job = -1;
    id_.par = 1;
    id_.sym = 2;
    id_.comm_fortran = -987654;  // MUMPS' USE_COMM_WORLD
    dmumps_c(&id_);
    id_.icntl[0] = id_.icntl[1] = id_.icntl[2] = id_.icntl[3] = 0;
    id_.icntl[5] = 0;     // no permutation from the values
    id_.icntl[6] = 3;     // SCOTCH
    id_.icntl[7] = 77;    // automatic scaling
    id_.icntl[9] = 0;     // no refinement
    id_.icntl[12] = 1;    // Ipopt's inertia setting
    id_.icntl[13] = 100;  // workspace margin
    id_.cntl[0] = 1e-6;   // pivot tolerance
    id_.n = pattern.dimension;
    for (int j = 0; j < pattern.dimension; ++j) {
      for (int e = pattern.column_starts[j]; e < pattern.column_starts[j + 1]; ++e) {
        rows_.push_back(pattern.rows[e] + 1);
        columns_.push_back(j + 1);
      }
    }
    id_.nnz = static_cast<int64_t>(rows_.size());
    id_.irn = rows_.data();
    id_.jcn = columns_.data();
    id_.job = 1;
    fesd::Stopwatch stopwatch;
    dmumps_c(&id_);
    analysis_seconds_ = stopwatch.wallSeconds();
    check("analysis");
  }
  ~MumpsReplay() {
    id_.job = -2;
    dmumps_c(&id_);
  }
  double analysisSeconds() const { return analysis_seconds_; }
  /// Factorises, returns the negative pivots.
  int factor(std::vector<double>& values) {
    id_.a = values.data();
    id_.job = 2;
    dmumps_c(&id_);
    check("factorisation");
    return id_.infog[11];
  }
  void solve(std::vector<double>& rhs) {
    id_.rhs = rhs.data();
    id_.job = 3;
    dmumps_c(&id_);
    check("solve");
  }
  long long factorEntries() const { return id_.infog[19]; }
  /// RINFOG(3): the floating-point operations of the last factorisation's elimination.
  double factorFlops() const { return id_.rinfog[2]; }

 private:
  void check(const char* what) const {
    if (id_.info[0] < 0) {
      throw std::runtime_error(std::string("MUMPS ") + what +
                               " failed: INFO(1) = " + std::to_string(id_.info[0]));
    }
  }
  DMUMPS_STRUC_C id_{};
  std::vector<int> rows_, columns_;
  double analysis_seconds_ = 0.0;
};

double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  return values[values.size() / 2];
}

/// b = A * ones, so every solve has the same well-defined answer.
std::vector<double> rightHandSide(const fesd::KktCapture::Matrix& matrix) {
  const fesd::linalg::LowerPattern& pattern = matrix.pattern;
  std::vector<double> rhs(pattern.dimension, 0.0);
  for (int j = 0; j < pattern.dimension; ++j) {
    for (int e = pattern.column_starts[j]; e < pattern.column_starts[j + 1]; ++e) {
      rhs[pattern.rows[e]] += matrix.values[e];
      if (pattern.rows[e] != j) rhs[j] += matrix.values[e];
    }
  }
  return rhs;
}

void replay(const std::string& scene, const std::vector<fesd::KktCapture::Matrix>& matrices,
            int repeats) {
  for (size_t k = 0; k < matrices.size(); ++k) {
    const fesd::KktCapture::Matrix& matrix = matrices[k];
    const std::vector<double> rhs = rightHandSide(matrix);
    fesd::Stopwatch analysis_clock;
    const std::shared_ptr<const fesd::linalg::SupernodalAnalysis> analysis =
        fesd::linalg::analyseKkt(matrix.pattern, matrix.constraint,
                                 fesd::linalg::FillOrdering::kAuto);
    const double our_analysis = analysis_clock.wallSeconds();
    fesd::linalg::MultifrontalLdlt ours(analysis);
    std::vector<double> our_factor, our_solve, mumps_factor, mumps_solve;
    int our_negative = 0, mumps_negative = 0, delayed = 0;
    double our_error = 0.0;
    for (int r = 0; r < repeats; ++r) {
      fesd::Stopwatch clock;
      const fesd::linalg::FactorReport report =
          ours.factor(matrix.values.data(), fesd::linalg::PivotSettings{});
      our_factor.push_back(clock.wallSeconds());
      our_negative = report.negative;
      delayed = report.delayed;
      std::vector<double> x = rhs;
      clock.restart();
      ours.solve(x.data());
      our_solve.push_back(clock.wallSeconds());
      our_error = 0.0;
      for (double value : x) our_error = std::max(our_error, std::abs(value - 1.0));
    }
    MumpsReplay mumps(matrix.pattern);
    std::vector<double> values = matrix.values;
    for (int r = 0; r < repeats; ++r) {
      fesd::Stopwatch clock;
      mumps_negative = mumps.factor(values);
      mumps_factor.push_back(clock.wallSeconds());
      std::vector<double> x = rhs;
      clock.restart();
      mumps.solve(x);
      mumps_solve.push_back(clock.wallSeconds());
    }
    std::printf(
        "replay scene=%s matrix=%zu n=%d nnz=%lld ordering=%s supernodes=%zu largest_front=%d "
        "flops=%.3g flops_mumps=%.3g fill_ours=%lld fill_mumps=%lld delayed=%d "
        "analysis_ms_ours=%.3f "
        "analysis_ms_mumps=%.3f "
        "factor_ms_ours=%.3f factor_ms_mumps=%.3f solve_ms_ours=%.3f solve_ms_mumps=%.3f "
        "error_vs_ones=%.1e negative_ours=%d "
        "negative_mumps=%d inertia=%s\n",
        scene.c_str(), k, matrix.pattern.dimension,
        static_cast<long long>(matrix.pattern.nonzeros()),
        analysis->ordering() == fesd::linalg::FillOrdering::kAmd ? "amd" : "metis",
        analysis->supernodes().size(), analysis->largestFront(), analysis->flops(),
        mumps.factorFlops(), static_cast<long long>(ours.factorEntries()), mumps.factorEntries(),
        delayed, 1e3 * our_analysis, 1e3 * mumps.analysisSeconds(), 1e3 * median(our_factor),
        1e3 * median(mumps_factor), 1e3 * median(our_solve), 1e3 * median(mumps_solve), our_error,
        our_negative, mumps_negative, our_negative == mumps_negative ? "agrees" : "DIFFERS");
  }
}

/// The task solved as solveSceneTask solves it under `linear_solver` and the budget, timed.
SolveFigures timedSolve(const fesd::SceneTask& task, fesd::SceneSolveOptions options,
                        const std::string& linear_solver, double budget) {
  options.ocp.homotopy.wall_time_budget = budget;
  options.ocp.homotopy.ipopt.linear_solver = linear_solver;
  fesd::Stopwatch clock;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  return SolveFigures{fesd::statusName(outcome.status), outcome.report.iterations,
                      outcome.report.objective, clock.wallSeconds()};
}

/// The scene's solve under `linear_solver`, as a function the bench can time.
std::function<SolveFigures(const std::string&)> sceneSolve(const std::string& scene, int intervals,
                                                           double budget) {
  if (scene == "panda") {
    return [budget](const std::string& linear_solver) {
      const fesd::SceneTask task = fesd::pandaPushTask(shippedRobot("panda_spherized.urdf"));
      fesd::SceneSolveOptions options;
      options.lazy_pairs = false;
      options.verify = true;
      return timedSolve(task, options, linear_solver, budget);
    };
  }
  const int rocks = scene == "default" ? 0 : 7;
  const bool all_pairs = scene == "all_pairs";
  if (scene != "default" && scene != "ten_discs" && !all_pairs) {
    throw std::invalid_argument("kkt-solvers: --scenes=default,ten_discs,all_pairs,panda");
  }
  return [=](const std::string& linear_solver) {
    const fesd::SceneTask task = showcaseWithRocks(intervals, rocks);
    fesd::SceneSolveOptions options;
    options.lazy_pairs = !all_pairs;
    return timedSolve(task, options, linear_solver, budget);
  };
}

}  // namespace

int kktSolvers(const Arguments& args) {
  const std::vector<std::string> scenes =
      args.texts("scenes", {"default", "ten_discs", "all_pairs", "panda"});
  const int intervals = args.integer("intervals", 40);
  const int keep = args.integer("keep", 2);
  const int repeats = args.integer("repeats", 3);
  const double budget = args.number("budget", 600.0);
  args.rejectUnused();
  int failures = 0;
  for (const std::string& scene : scenes) {
    const auto solve = sceneSolve(scene, intervals, budget);
    std::vector<fesd::KktCapture::Matrix> matrices;
    for (const char* linear_solver : {fesd::kLdltSolver, "mumps"}) {
      fesd::KktCapture capture(linear_solver == std::string("mumps") ? 0 : keep);
      const SolveFigures figures = solve(linear_solver);
      const fesd::KktCapture::Totals& totals = capture.totals();
      std::printf(
          "solve scene=%s linear_solver=%s status=%s iterations=%d objective=%.12g wall_s=%.3f",
          scene.c_str(), linear_solver, figures.status.c_str(), figures.iterations,
          figures.objective, figures.seconds);
      if (totals.factorisations > 0) {
        std::printf(
            " analyses=%d analysis_s=%.4f factorisations=%d factor_s=%.4f solves=%d "
            "solve_s=%.4f delayed_pivots=%d two_by_two_pivots=%d largest_n=%d "
            "largest_fill=%lld",
            totals.analyses, totals.analysis_seconds, totals.factorisations, totals.factor_seconds,
            totals.solves, totals.solve_seconds, totals.delayed_pivots, totals.two_by_two_pivots,
            totals.largest_dimension, totals.factor_entries);
      }
      std::printf("\n");
      std::fflush(stdout);
      failures += figures.status != "success";
      if (!capture.matrices().empty()) matrices = capture.matrices();
    }
    replay(scene, matrices, repeats);
  }
  return failures == 0 ? 0 : 1;
}

}  // namespace fesd_bench
