#pragma once

#include <array>
#include <atomic>
#include <cmath>
#include <functional>
#include <memory>
#include <unordered_map>
#include <utility>
#include <vector>

#include "fesd_trajopt/nlp/helper_thread.h"
#include "fesd_trajopt/nlp/nlp_problem.h"

namespace fesd {

/// Maps matrix coordinates to slots of a value array, merging repeated coordinates.
class SlotMap {
 public:
  int slot(int row, int col);
  const SparsityPattern& pattern() const { return pattern_; }

 private:
  SparsityPattern pattern_;
  std::unordered_map<long long, int> index_;
};

/// A sparse NLP assembled from three kinds of pieces:
///  - linear parts of rows (constant Jacobian entries),
///  - bilinear rows (a^T x)(b^T x), used for (relaxed) complementarity constraints,
///  - function terms: coefficient * [scale variable] * F(z) added to rows or to the objective,
///    where F is a SmoothFunction evaluated at a vector z of variables.
/// Patterns and value slots are fixed by finalize(); evaluation then only writes into slots.
/// Bounds and the relaxation may change between solves without changing the structure.
class NlpAssembly : public RelaxedMpcc {
 public:
  static constexpr int kObjective = -1;  ///< "row" of a function term that feeds the objective
  static constexpr double kInfinity = 1e20;
  /// A fixed variable (data, or a side fixed by fixActiveSet) of at most this size counts as
  /// zero in active-set decisions: c(x) at a point on a curved boundary is zero only to rounding.
  static constexpr double kNegligibleFixedValue = 1e-9;

  /// Adds `count` variables with common bounds and initial value; returns the first index.
  int addVariables(int count, double lower, double upper, double initial = 0.0);
  /// Adds `count` rows with common bounds; returns the first index.
  int addRows(int count, double lower, double upper);
  /// Adds `count` equality rows relaxed like the complementarity:
  /// -scale * sigma <= g <= scale * sigma.
  int addRelaxedRows(int count, double scale = 1.0);
  void addLinear(int row, int variable, double coefficient);
  void addLinear(int row, const LinearExpression& expression);
  /// Adds the row (left^T x)(right^T x) <= sigma, counted as a complementarity constraint.
  /// Active-set decisions compare the sides as left_weight left^T x against
  /// right_weight right^T x (the weights bring them to one unit).
  int addComplementarity(const LinearExpression& left, const LinearExpression& right,
                         double left_weight = 1.0, double right_weight = 1.0);
  /// Adds sum_targets coefficient * x[scale_variable] * F(x[inputs]) to rows
  /// [target_row, target_row + F.outputSize()) or to the objective (target_row = kObjective).
  /// scale_variable < 0 means a scale of one.
  struct Target {
    int row;
    double coefficient;
    bool scaled_by_relaxation = false;  ///< coefficient * sigma: a term that vanishes with sigma
  };
  void addFunctionTerm(std::shared_ptr<const SmoothFunction> function, std::vector<int> inputs,
                       int scale_variable, std::vector<Target> targets);
  void finalize();
  /// How many threads evaluate the function terms: measured (values, Jacobian and Hessian each
  /// on two once kSlowEvaluations of them in a row took kTwoThreadSeconds on one), or one or two
  /// always. The values are the same bits either way.
  enum class Threads { kMeasured, kOne, kTwo };
  void setEvaluationThreads(Threads threads);
  static constexpr double kTwoThreadSeconds = 500e-6;

  void setVariableBounds(int variable, double lower, double upper);
  void setRowBounds(int row, double lower, double upper);
  /// Called at the end of fixActiveSet with the point it was given; may change any bounds,
  /// which releaseActiveSet restores with the rest.
  void setActiveSetHook(std::function<void(const double* x)> hook) { hook_ = std::move(hook); }

  double variableLower(int variable) const { return x_lower_[variable]; }
  double variableUpper(int variable) const { return x_upper_[variable]; }
  /// Fixed (by the active set, or as data) at a value within kNegligibleFixedValue of zero, or
  /// a side of a pair the fixed active set leaves biactive (zero in the active set's meaning,
  /// though left to the NLP; setBiactiveRule).
  bool fixedAtAboutZero(int variable) const {
    return fixedNearZero(variable) ||
           (!biactive_variables_.empty() && biactive_variables_[variable]);
  }
  std::vector<double>& initialGuess() { return initial_; }
  const std::vector<double>& initialGuess() const { return initial_; }

  // NlpProblem / RelaxedMpcc
  int numVariables() const override { return static_cast<int>(x_lower_.size()); }
  int numConstraints() const override { return static_cast<int>(g_lower_.size()); }
  void getBounds(double* x_lower, double* x_upper, double* g_lower, double* g_upper) const override;
  double objective(const double* x) const override;
  void objectiveGradient(const double* x, double* gradient) const override;
  void constraints(const double* x, double* g) const override;
  const SparsityPattern& jacobianPattern() const override { return jacobian_slots_.pattern(); }
  void jacobian(const double* x, double* values) const override;
  const SparsityPattern& hessianPattern() const override { return hessian_slots_.pattern(); }
  void hessian(const double* x, double objective_factor, const double* multipliers,
               double* values) const override;
  void setRelaxation(double sigma) override;
  double relaxation() const override { return sigma_; }
  void setVanishingTermsWeight(double weight) override { vanishing_weight_ = weight; }
  int numComplementarities() const override {
    return static_cast<int>(complementarity_rows_.size());
  }
  const std::vector<int>& complementarityRows() const override { return complementarity_rows_; }
  double complementarityResidual(const double* x) const override;
  /// The same with the sides' data (fixed variables) within kNegligibleFixedValue of zero taken
  /// as zero, as fixGivenActiveSet takes them, and the `left_free` variables' terms left out:
  /// what the unknowns of an active set fixed with those left free leave.
  double complementarityResidualOfUnknowns(const double* x,
                                           const std::vector<int>& left_free = {}) const;
  /// The rows of the complementarities that have a term in one of `variables`.
  std::vector<int> complementarityRowsWith(const std::vector<int>& variables) const;
  /// Largest |g_i(x) - b_i| over the equality rows (dynamics and algebraic equations): how far
  /// a guess is from satisfying them.
  double equalityResidual(const double* x) const;
  std::vector<bool> identifyActiveSet(const double* x) const override;
  bool fixActiveSet(const double* x, int flip = -1) override;
  void setBiactiveRule(double fraction, double sigma) override {
    biactive_fraction_ = fraction;
    biactive_sigma_ = sigma;
  }
  bool fixGivenActiveSet(const std::vector<bool>& left_is_zero, const double* x) override;
  /// The same, leaving the `left_free` variables free (>= 0) although they are on zero sides
  /// (Discretization::jumpingForces).
  bool fixGivenActiveSet(const std::vector<bool>& left_is_zero, const double* x,
                         const std::vector<int>& left_free);
  std::vector<bool> flipBiactivePairs(const double* x) const override;
  void releaseActiveSet() override;
  double biactiveDescent(const double* x, const double* multipliers) const override;
  std::vector<FixedPair> fixedPairs() const override;
  void boundsBeforeActiveSet(double* x_lower, double* x_upper) const override;

 private:
  struct LinearEntry {
    int row, variable;
    double coefficient;
    int slot = -1;
  };
  struct Complementarity {
    int row;
    LinearExpression left, right;
    double left_weight, right_weight;
    std::vector<int> left_slots, right_slots;  // Jacobian
    std::vector<int> pair_slots;               // Hessian, left-major
  };
  struct FunctionTerm {
    std::shared_ptr<const SmoothFunction> function;
    std::vector<int> inputs;
    int scale_variable;
    std::vector<Target> targets;
    std::vector<int> jacobian_slots;        // per target, per Jacobian entry
    std::vector<int> scale_jacobian_slots;  // per target, per output
    std::vector<int> hessian_slots;         // per Hessian entry
    std::vector<int> scale_hessian_slots;   // per input (-1 when F does not depend on it)
    size_t span = 0;                        ///< where its TermSpan starts in term_spans_
  };
  /// One term's evaluations in one array: F's values, Jacobian, Hessian and the weights of its
  /// outputs in the Hessian.
  struct TermSpan {
    TermSpan(const SmoothFunction& f, double* start)
        : values(start),
          jacobian(values + f.outputSize()),
          hessian(jacobian + f.jacobianPattern().nonzeros()),
          weights(hessian + f.hessianPattern().nonzeros()) {}
    static size_t size(const SmoothFunction& f) {
      return 2 * f.outputSize() + f.jacobianPattern().nonzeros() + f.hessianPattern().nonzeros();
    }
    double *values, *jacobian, *hessian, *weights;
  };
  /// Evaluates a term at its arguments z (with the function given: another thread's copy).
  using TermEvaluation =
      std::function<void(const FunctionTerm&, const SmoothFunction&, const double* z, TermSpan&)>;
  /// Adds an evaluated term into the NLP's values.
  using TermAddition = std::function<void(const FunctionTerm&, const TermSpan&)>;
  enum class Pass { kValues, kJacobian, kHessian };
  /// Every term evaluated at x and added in the terms' order: the same bits on one thread or two
  /// (each term into its own span; this thread adds the spans in order as they are done).
  void forEachTerm(Pass pass, const double* x, const TermEvaluation& evaluate,
                   const TermAddition& add) const;
  void forEachTermOnOneThread(const double* x, const TermEvaluation& evaluate,
                              const TermAddition& add) const;
  void forEachTermOnTwoThreads(const double* x, const TermEvaluation& evaluate,
                               const TermAddition& add) const;
  /// Makes the helper thread and the functions it evaluates; false (and nothing kept) if that
  /// fails.
  bool startHelper() const;
  /// The active set fixActiveSet would fix at x: per pair whether the left side is the zero
  /// one, and how ambiguous the choice is (min/max of the two sides; 0 when data decides).
  struct ActiveSetChoice {
    bool valid = true;  ///< false when some pair has fixed nonzero data on both sides
    std::vector<bool> left_is_zero;
    std::vector<double> ambiguity;  ///< 0 for biactive pairs: there is nothing to flip
    std::vector<bool> biactive;     ///< both sides vanish (setBiactiveRule): neither is fixed
  };
  ActiveSetChoice chooseActiveSet(const double* x) const;
  void checkNotFinalized() const;
  void checkFinalized() const;
  /// Weights w_r = sum_t coefficient_t * multiplier(row_t + r) of one term's outputs.
  void termWeights(const FunctionTerm& term, double objective_factor, const double* multipliers,
                   double* weights) const;
  double coefficient(const Target& target) const {
    return target.scaled_by_relaxation ? target.coefficient * sigma_ * vanishing_weight_
                                       : target.coefficient;
  }

  std::vector<double> x_lower_, x_upper_, initial_, g_lower_, g_upper_;
  std::vector<LinearEntry> linear_;
  std::vector<Complementarity> complementarities_;
  std::vector<int> complementarity_rows_;
  std::vector<std::pair<int, double>> relaxed_rows_;  ///< row, scale
  std::vector<FunctionTerm> terms_;
  SlotMap jacobian_slots_, hessian_slots_;
  double sigma_ = 0.0;
  double vanishing_weight_ = 1.0;
  bool finalized_ = false;
  /// Bounds before fixActiveSet (empty: not fixed).
  std::vector<double> saved_x_lower_, saved_x_upper_, saved_g_lower_, saved_g_upper_;
  /// Per pair while an active set is fixed: whether its left side is the one fixed to zero.
  std::vector<bool> fixed_left_;
  std::function<void(const double* x)> hook_;
  double biactive_fraction_ = 0.0, biactive_sigma_ = 0.0;  ///< setBiactiveRule
  /// While an active set is fixed: the pairs it leaves biactive, and their variables (empty when
  /// there are none).
  std::vector<bool> biactive_pairs_, biactive_variables_;
  /// fixGivenActiveSet, leaving the `biactive` pairs' sides free.
  /// Fixed (lower = upper: data, or a side the active set fixed), and within
  /// kNegligibleFixedValue of zero.
  bool fixed(int variable) const { return x_lower_[variable] == x_upper_[variable]; }
  bool fixedNearZero(int variable) const {
    return fixed(variable) && std::fabs(x_lower_[variable]) <= kNegligibleFixedValue;
  }
  /// The largest |left * right| over the pairs, `without_negligible_fixed`: leaving out the
  /// sides' terms fixedNearZero and those of the `left_out` variables.
  double largestProduct(const double* x, bool without_negligible_fixed,
                        const std::vector<int>& left_out = {}) const;
  bool fixPairs(const std::vector<bool>& left_is_zero, const std::vector<bool>& biactive,
                const double* x, const std::vector<int>& left_free = {});
  // One function term's arguments and span, sized to the largest term (a thread's own).
  mutable std::vector<double> scratch_inputs_, scratch_span_;
  static constexpr int kTermsPerChunk = 16;  ///< what a thread claims at a time
  static constexpr int kSlowEvaluations = 3;
  /// How a pass is evaluated; while measured, its slow evaluations in a row.
  struct PassThreads {
    Threads mode = Threads::kMeasured;
    int slow = 0;
  };
  mutable std::array<PassThreads, 3> pass_threads_;  ///< per Pass
  /// For two threads: the helper thread, the function each term evaluates there (its copy,
  /// where it keeps state), the helper's arguments and every term's span. Made when first used.
  mutable std::unique_ptr<HelperThread> helper_;
  mutable std::vector<std::shared_ptr<const SmoothFunction>> helper_functions_;
  mutable std::vector<double> helper_inputs_, term_spans_;
  mutable std::unique_ptr<std::atomic<bool>[]> chunk_done_;  ///< per chunk of terms
};

}  // namespace fesd
