#pragma once

#include <cstdint>
#include <memory>
#include <vector>

#include "fesd_trajopt/linalg/front_factorization.h"
#include "fesd_trajopt/linalg/supernodal_analysis.h"

namespace fesd::linalg {

/// What a factorisation did.
struct FactorReport {
  int negative = 0;    ///< negative eigenvalues (the inertia Ipopt asks for)
  int two_by_two = 0;  ///< 2x2 pivots
  int delayed = 0;     ///< columns passed to a parent front because no pivot in theirs passed
  int zero = 0;        ///< zero pivots: > 0 means singular (the factors are then incomplete)
  bool finite = true;
  bool usable() const { return finite && zero == 0; }
};

/// How a refined solve went: refinement steps against the matrix as given, and the scaled
/// residual |b - A x|_inf / (|A|_max |x|_inf + |b|_inf) it ended with.
struct SolveReport {
  int refinement_steps = 0;
  double residual = 0.0;
};

/// The numeric LDL^T factorisation of symmetric indefinite matrices with one analysed pattern:
/// multifrontal over the analysis' supernodes, dense fronts with threshold pivoting (1x1 and 2x2
/// pivots, columns delayed to the parent front where no pivot passes). Memory is taken at
/// construction and grows only when delayed pivots need larger fronts than any before; a
/// factorisation or solve otherwise allocates nothing. One object per thread; the analysis is
/// shared.
class MultifrontalLdlt {
 public:
  explicit MultifrontalLdlt(std::shared_ptr<const SupernodalAnalysis> analysis);

  /// Factorises the matrix whose lower-triangle values come in the pattern's entry order.
  FactorReport factor(const double* values, const PivotSettings& settings);
  /// Solves A x = b in place (b in, x out) with the factors.
  void solve(double* rhs) const;
  /// solve, then refinement against the matrix as factorised until the scaled residual is at
  /// most `tolerance` or stops shrinking, at most `max_steps` times.
  SolveReport solveRefined(double* rhs, double tolerance, int max_steps);

  const SupernodalAnalysis& analysis() const { return *analysis_; }
  const FactorReport& report() const { return report_; }
  bool factorised() const { return factorised_; }
  int64_t factorEntries() const { return factor_used_; }  ///< L's stored values, with delays

 private:
  /// One supernode's part of the factors.
  struct Block {
    int64_t values = 0;  ///< offset of its rows x eliminated L block
    int64_t labels = 0;  ///< offset of its rows' labels (elimination positions)
    int64_t pivots = 0;  ///< offset of its pivots in diagonal_ / off_diagonal_
    int rows = 0, eliminated = 0;
  };
  /// An update matrix waiting on the stack for its parent.
  struct Update {
    int supernode;
    int64_t values, labels;
    int size, delayed;
  };

  void assemble(int s, int own, int delayed, int rows, const double* values);
  void solvePermuted(double* y) const;
  double scaledResidual(const double* rhs, const double* x, double* residual) const;
  template <class T>
  static T* room(std::vector<T>& buffer, int64_t used, int64_t needed);

  std::shared_ptr<const SupernodalAnalysis> analysis_;
  std::vector<double> values_;  ///< the matrix as factorised, for refinement
  double matrix_norm_ = 0.0;    ///< |A|_max
  std::vector<Block> blocks_;
  std::vector<double> factor_, diagonal_, off_diagonal_;
  std::vector<int> labels_;
  int64_t factor_used_ = 0, labels_used_ = 0;
  std::vector<double> front_, work_, stack_;
  std::vector<int> front_labels_, stack_labels_, where_;
  std::vector<Update> updates_;
  mutable std::vector<double> permuted_, gathered_, below_;
  std::vector<double> rhs_, residual_, correction_, best_;
  FactorReport report_;
  bool factorised_ = false;
};

}  // namespace fesd::linalg
