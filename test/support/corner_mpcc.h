#pragma once

#include "fesd_trajopt/function/affine_function.h"
#include "fesd_trajopt/function/quadratic_function.h"
#include "fesd_trajopt/nlp/nlp_assembly.h"
#include "fesd_trajopt/solver/mpcc_solver.h"

namespace fesd_test {

/// min (x-1)^2 + (y-target_y)^2  s.t.  0 <= x _|_ y >= 0. With target_y = 1 (default): minimisers
/// (1, 0) and (0, 1), value 1; with target_y = -1: the minimiser (1, 0), value 1, and the origin,
/// the solution of the branch x = 0 (value 2), which is not B-stationary.
/// `Assembly` may be an NlpAssembly subclass that injects faults.
template <class Assembly = fesd::NlpAssembly>
struct CornerMpcc {
  Assembly nlp;
  int x, y;
  explicit CornerMpcc(double target_y = 1.0) {
    x = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    y = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    nlp.addFunctionTerm(fesd::QuadraticFunction::weightedDistance(Eigen::Vector2d::Ones(),
                                                                  Eigen::Vector2d(1.0, target_y)),
                        {x, y}, -1, {{fesd::NlpAssembly::kObjective, 1.0}});
    nlp.addComplementarity({{x, 1.0}}, {{y, 1.0}});
  }
  fesd::MpccReport solve(const fesd::HomotopyOptions& options = {}) {
    nlp.finalize();
    return fesd::MpccSolver(options).solve(nlp, {1.0, 0.5});
  }
};

/// Cuts `corner` (not finalized) at x <= 1 - 1e-4 and solves it from the plan (1, 0.3), whose
/// active set (y = 0) is polished for one Ipopt iteration only, so that the polish stops unsolved
/// and the homotopy follows from sigma 1e-4: from the plan, or from the polish's iterate where
/// `resume`.
template <class Assembly>
fesd::MpccReport solveCutCornerAfterAnUnsolvedPolish(CornerMpcc<Assembly>& corner, bool resume) {
  corner.nlp.addLinear(corner.nlp.addRows(1, -fesd::NlpAssembly::kInfinity, 1.0 - 1e-4),
                       {{corner.x, 1.0}});
  corner.nlp.finalize();
  fesd::MpccReport plan;
  plan.solution = {1.0, 0.3};
  fesd::HomotopyOptions options;
  options.polish_previous_always = true;
  options.previous_polish_iterations = 1;
  options.resume_from_unsolved_polish = resume;
  return fesd::MpccSolver(options).solve(corner.nlp, plan, 1e-4);
}

/// min -x  s.t.  y = x,  0 <= x _|_ y >= 0 (not finalized): the origin is the only feasible point,
/// so it is B-stationary, but on the branch x = 0 the row y = x holds the free side y at 0 too
/// and no multiplier has the multiplier test's signs (d Lagrangian / dx = -1 - z_y < 0).
struct OnlyTheOrigin {
  fesd::NlpAssembly nlp;
  int x, y;
  OnlyTheOrigin() {
    x = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    y = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    nlp.addLinear(nlp.addRows(1, 0.0, 0.0), {{y, 1.0}, {x, -1.0}});
    Eigen::SparseMatrix<double> minus_x(1, 1);
    minus_x.insert(0, 0) = -1.0;
    nlp.addFunctionTerm(std::make_shared<fesd::AffineFunction>(minus_x, Eigen::VectorXd::Zero(1)),
                        {x}, -1, {{fesd::NlpAssembly::kObjective, 1.0}});
    nlp.addComplementarity({{x, 1.0}}, {{y, 1.0}});
  }
  /// Adds a second pair, u = 1 _|_ v = 0 (min (u - 1)^2 + v^2), the scale on which y counts as
  /// zero, and finalizes; a start is (0.5, 0.5, 1, 0.1).
  void addScalePairAndFinalize() {
    const int u = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    const int v = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    nlp.addFunctionTerm(fesd::QuadraticFunction::weightedDistance(Eigen::Vector2d::Ones(),
                                                                  Eigen::Vector2d(1.0, 0.0)),
                        {u, v}, -1, {{fesd::NlpAssembly::kObjective, 1.0}});
    nlp.addComplementarity({{u, 1.0}}, {{v, 1.0}});
    nlp.finalize();
  }
  /// Solved from (0.5, 0.5, 1, 0.1) with the scale pair, polished early (sigma 1e-2), and a branch
  /// check of one iteration, which cannot solve the other branch.
  fesd::MpccReport solveWithAnUnsolvedBranchCheck(bool accept_unsolved) {
    addScalePairAndFinalize();
    fesd::HomotopyOptions options;
    options.early_polish_sigma = 1e-2;
    options.branch_check_iterations = 1;
    options.accept_unsolved_branch_check = accept_unsolved;
    return fesd::MpccSolver(options).solve(nlp, {0.5, 0.5, 1.0, 0.1});
  }
};

}  // namespace fesd_test
