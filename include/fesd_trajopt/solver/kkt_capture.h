#pragma once

#include <vector>

#include "fesd_trajopt/linalg/supernodal_analysis.h"

namespace fesd {

/// Watches the KKT systems that Ipopt hands our LDL^T (IpoptSettings::linear_solver kLdltSolver)
/// in this thread while it exists: counts and times every analysis, factorisation and solve,
/// and keeps the first `keep` matrices, for benchmarks and tests. Captures nest: the innermost
/// one watches.
class KktCapture {
 public:
  explicit KktCapture(int keep = 0);
  ~KktCapture();
  KktCapture(const KktCapture&) = delete;
  KktCapture& operator=(const KktCapture&) = delete;

  struct Matrix {
    linalg::LowerPattern pattern;
    std::vector<double> values;    ///< in the pattern's entry order
    std::vector<char> constraint;  ///< Ipopt's constraint rows
    int negative_pivots = 0;
  };
  struct Totals {
    int analyses = 0, factorisations = 0, solves = 0, delayed_pivots = 0, two_by_two_pivots = 0;
    int inertia_told = 0;  ///< factorisations whose inertia Ipopt's interface object was told
    double analysis_seconds = 0.0, factor_seconds = 0.0, solve_seconds = 0.0;
    int largest_dimension = 0;
    long long factor_entries = 0;  ///< of the largest system
  };

  const std::vector<Matrix>& matrices() const { return matrices_; }
  const Totals& totals() const { return totals_; }

  /// The capture watching this thread, or nullptr.
  static KktCapture* active();
  /// Called by the linear solver.
  void addMatrix(Matrix matrix);
  Totals& mutableTotals() { return totals_; }
  bool wantsMatrix() const { return static_cast<int>(matrices_.size()) < keep_; }

 private:
  int keep_;
  std::vector<Matrix> matrices_;
  Totals totals_;
  KktCapture* outer_;
};

}  // namespace fesd
