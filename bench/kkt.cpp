// kkt: the showcase scene with extra passive discs ("rocks") in reach, its NLP's sparsity (sizes,
// densest Jacobian rows and columns, KKT degrees) and one solve (iterations, times), to study
// what one Ipopt iteration costs as the scene grows.
#include <algorithm>
#include <cstdio>
#include <fstream>
#include <numeric>
#include <stdexcept>
#include <string>
#include <vector>

#include "bench_scenes.h"
#include "commands.h"
#include "fesd_trajopt/examples/manipulation_example.h"
#include "fesd_trajopt/ocp/ocp_solver.h"
#include "fesd_trajopt/planning/scene_solver.h"
#include "fesd_trajopt/scene/moving_part.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd_bench {
namespace {

/// Per node of the KKT graph (variables, then rows): its neighbours (Hessian off-diagonals and
/// Jacobian entries).
void printStructure(const fesd::NlpAssembly& nlp, const std::string& dump) {
  const int n = nlp.numVariables(), m = nlp.numConstraints();
  const fesd::SparsityPattern& jac = nlp.jacobianPattern();
  const fesd::SparsityPattern& hess = nlp.hessianPattern();
  std::vector<int> row_nnz(m, 0), col_nnz(n, 0), hess_degree(n, 0);
  for (int e = 0; e < jac.nonzeros(); ++e) {
    ++row_nnz[jac.rows[e]];
    ++col_nnz[jac.cols[e]];
  }
  int hess_diagonal = 0;
  for (int e = 0; e < hess.nonzeros(); ++e) {
    if (hess.rows[e] == hess.cols[e]) {
      ++hess_diagonal;
      continue;
    }
    ++hess_degree[hess.rows[e]];
    ++hess_degree[hess.cols[e]];
  }
  auto top = [](const std::vector<int>& degree, int count) {
    std::vector<int> order(degree.size());
    std::iota(order.begin(), order.end(), 0);
    std::partial_sort(order.begin(), order.begin() + std::min<size_t>(count, order.size()),
                      order.end(), [&](int a, int b) { return degree[a] > degree[b]; });
    order.resize(std::min<size_t>(count, order.size()));
    std::string text;
    for (int i : order) text += std::to_string(i) + ":" + std::to_string(degree[i]) + " ";
    return text;
  };
  auto mean = [](const std::vector<int>& v) {
    return v.empty() ? 0.0 : std::accumulate(v.begin(), v.end(), 0.0) / v.size();
  };
  std::vector<int> kkt_degree(n + m, 0);
  for (int j = 0; j < n; ++j) kkt_degree[j] = hess_degree[j] + col_nnz[j];
  for (int r = 0; r < m; ++r) kkt_degree[n + r] = row_nnz[r];
  std::printf("variables=%d constraints=%d jacobian_nnz=%d hessian_nnz=%d (diagonal %d)\n", n, m,
              jac.nonzeros(), hess.nonzeros(), hess_diagonal);
  std::printf("kkt_nnz_lower=%d (hessian + jacobian + n + m diagonals) nnz_per_variable=%.2f\n",
              hess.nonzeros() - hess_diagonal + jac.nonzeros() + n + m,
              double(jac.nonzeros() + hess.nonzeros()) / n);
  std::printf("jacobian rows: mean %.2f nnz, densest (row:nnz) %s\n", mean(row_nnz),
              top(row_nnz, 8).c_str());
  std::printf("jacobian cols: mean %.2f nnz, densest (col:nnz) %s\n", mean(col_nnz),
              top(col_nnz, 8).c_str());
  std::printf("hessian off-diagonal degree: mean %.2f, largest (var:degree) %s\n",
              mean(hess_degree), top(hess_degree, 8).c_str());
  std::printf("kkt degree: largest (node:degree, rows from %d) %s\n", n,
              top(kkt_degree, 10).c_str());
  if (!dump.empty()) {
    std::ofstream j(dump + "_jacobian.txt"), h(dump + "_hessian.txt");
    j << n << " " << m << " " << jac.nonzeros() << "\n";
    for (int e = 0; e < jac.nonzeros(); ++e) j << jac.rows[e] << " " << jac.cols[e] << "\n";
    h << n << " " << hess.nonzeros() << "\n";
    for (int e = 0; e < hess.nonzeros(); ++e) h << hess.rows[e] << " " << hess.cols[e] << "\n";
    std::printf("dumped %s_jacobian.txt, %s_hessian.txt\n", dump.c_str(), dump.c_str());
  }
}

}  // namespace

int kkt(const Arguments& args) {
  const int intervals = args.integer("intervals", 40);
  const int rocks = args.integer("rocks", 7);
  const bool solve = args.flag("solve", true);
  const bool history = args.flag("history", false);
  const std::string dump = args.text("dump", "");
  fesd::SceneSolveOptions options;
  options.lazy_pairs = false;  // the study: every pair in reach in the NLP
  options.ocp.discretization.num_elements = args.integer("elements", 3);
  options.ocp.discretization.num_stages = args.integer("stages", 2);
  options.ocp.homotopy.wall_time_budget = args.number("budget", 600.0);
  applyHomotopyArguments(args, options.ocp.homotopy);
  args.rejectUnused();
  if (rocks < 0 || rocks > 7) throw std::invalid_argument("kkt: --rocks=0..7");

  const fesd::SceneTask task = showcaseWithRocks(intervals, rocks);
  {
    fesd::SceneOutcome prepared;
    prepared.decisions = fesd::decidePairs(task);
    const fesd::MovingPart part = fesd::movingPart(task, prepared.decisions);
    const fesd::OcpDefinition ocp = fesd::buildOcp(part.task, part.modelled);
    fesd::OcpSolver solver(ocp, options.ocp);
    std::printf("intervals=%d rocks=%d moving_bodies=%zu modelled_pairs=%zu\n", intervals, rocks,
                part.bodies.size(), part.modelled.size());
    printStructure(solver.discretization().nlp(), dump);
  }
  if (!solve) return 0;
  fesd::Stopwatch stopwatch;
  const fesd::SceneOutcome outcome = fesd::solveSceneTask(task, fesd::TaskLimits{}, options);
  const fesd::MpccReport& report = outcome.report;
  if (history) {
    for (const fesd::HomotopyStep& step : report.history) {
      std::printf("nlp sigma=%.1e iterations=%d status=%s wall_s=%.3f objective=%.12g\n",
                  step.sigma, step.iterations, step.ipopt_status.c_str(), step.wall_seconds,
                  step.objective);
    }
  }
  std::printf(
      "status=%s iterations=%d nlps=%zu objective=%.12g residual=%.2e wall_s=%.3f ipopt_s=%.3f "
      "evaluation_s=%.3f per_iteration_ms=%.2f total_s=%.3f main_thread_cpu_s=%.3f\n",
      fesd::statusName(outcome.status).c_str(), report.iterations, report.history.size(),
      report.objective, report.complementarity_residual, report.wall_seconds, report.ipopt_seconds,
      report.evaluation_seconds,
      report.iterations > 0 ? 1e3 * report.ipopt_seconds / report.iterations : 0.0,
      stopwatch.wallSeconds(), report.cpu_seconds);
  return outcome.status == fesd::SolveStatus::kSuccess ? 0 : 1;
}

}  // namespace fesd_bench
