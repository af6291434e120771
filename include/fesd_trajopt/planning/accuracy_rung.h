#pragma once

#include <limits>
#include <string>
#include <vector>

#include "fesd_trajopt/solver/mpcc_solver.h"

namespace fesd {

/// One rung of an accuracy ladder: a solve on its discretisation and its verification, and what
/// it changed from the rung before and why.
struct AccuracyRung {
  int stages = 0;
  std::vector<int> interval_elements;  ///< elements per control interval
  std::string change;                  ///< what this rung changed ("" on the first)
  std::string reason;                  ///< the blame that called for it ("" on the first)
  std::vector<int> refined_intervals;  ///< the intervals it gave more elements or held grazes in
  /// The largest interval error of the rung before, where this one refines (NaN on the first).
  double error_before = std::numeric_limits<double>::quiet_NaN();
  /// The verification's largest interval error; infinity when unverified or failed.
  double verification_error = std::numeric_limits<double>::infinity();
  int grazes = 0;  ///< contacts its plan cuts into between stage points (it cannot succeed)
  /// Started from the rung before's plan (else: the first rung, or the cold path after that
  /// failed, which `change` says).
  bool from_previous_plan = false;
  double wall_seconds = 0.0;
  SolveStatus status = SolveStatus::kSolverError;
};

/// Whether an outcome of this status is a solution of its NLP: a success, or one whose only
/// shortfall is a target it did not reach or an accuracy it did not meet (a plan all the same,
/// to execute or replan from).
bool solvedItsNlp(SolveStatus status);

}  // namespace fesd
