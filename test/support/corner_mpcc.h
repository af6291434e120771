#pragma once

#include "fesd_trajopt/function/quadratic_function.h"
#include "fesd_trajopt/nlp/nlp_assembly.h"
#include "fesd_trajopt/solver/mpcc_solver.h"

namespace fesd_test {

/// min (x-1)^2 + (y-1)^2  s.t.  0 <= x _|_ y >= 0: minimisers (1, 0) and (0, 1), value 1.
/// `Assembly` may be an NlpAssembly subclass that injects faults.
template <class Assembly = fesd::NlpAssembly>
struct CornerMpcc {
  Assembly nlp;
  int x, y;
  CornerMpcc() {
    x = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    y = nlp.addVariables(1, 0.0, fesd::NlpAssembly::kInfinity);
    nlp.addFunctionTerm(
        fesd::QuadraticFunction::weightedDistance(Eigen::Vector2d::Ones(), Eigen::Vector2d::Ones()),
        {x, y}, -1, {{fesd::NlpAssembly::kObjective, 1.0}});
    nlp.addComplementarity({{x, 1.0}}, {{y, 1.0}});
  }
  fesd::MpccReport solve(const fesd::HomotopyOptions& options = {}) {
    nlp.finalize();
    return fesd::MpccSolver(options).solve(nlp, {1.0, 0.5});
  }
};

}  // namespace fesd_test
