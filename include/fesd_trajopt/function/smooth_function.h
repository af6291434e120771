#pragma once

#include <functional>
#include <memory>
#include <unordered_map>
#include <vector>

namespace fesd {

/// Coordinates of the structurally nonzero entries of a sparse matrix, in a fixed order that the
/// matching value arrays follow.
struct SparsityPattern {
  std::vector<int> rows;
  std::vector<int> cols;

  int nonzeros() const { return static_cast<int>(rows.size()); }
  void add(int row, int col) {
    rows.push_back(row);
    cols.push_back(col);
  }
  /// Every entry of a rows x cols matrix (lower triangle only when `lower_triangle`).
  static SparsityPattern dense(int num_rows, int num_cols, bool lower_triangle = false);
};

class SmoothFunction;

/// The copies of functions made for one more thread. State that several functions share (a
/// robot's kinematics at the states it was evaluated at) is copied once, so that the copies of
/// those functions share its copy as the originals share it.
class ThreadCopies {
 public:
  /// The copy of `original` for this thread, made by `make` the first time it is asked for.
  template <class T>
  std::shared_ptr<const T> of(const T* original,
                              const std::function<std::shared_ptr<const T>()>& make) {
    const auto kept = copies_.find(original);
    if (kept != copies_.end()) return std::static_pointer_cast<const T>(kept->second);
    std::shared_ptr<const T> copy = make();  // may ask for copies itself
    copies_[original] = copy;
    return copy;
  }
  /// The function to evaluate in this thread: its copy, or itself where it keeps no state.
  std::shared_ptr<const SmoothFunction> function(const std::shared_ptr<const SmoothFunction>& f);

 private:
  std::unordered_map<const void*, std::shared_ptr<const void>> copies_;  ///< null: shared
};

/// A twice continuously differentiable map y = F(z) on a small argument, with exact sparse
/// derivatives. Everything the discretised problem evaluates (the DCS velocity, the constraint
/// functions, costs, path constraints) is one of these, evaluated at many points.
///
/// Functions may be evaluated by several threads at once (NlpAssembly does for large problems):
/// one that keeps state between calls (scratch buffers, a cache) must give each thread its own
/// copy through threadCopy.
class SmoothFunction {
 public:
  virtual ~SmoothFunction() = default;

  /// A copy for another thread to evaluate while this one is evaluated, or nullptr where this
  /// function keeps no state between calls and may be shared.
  virtual std::shared_ptr<const SmoothFunction> threadCopy(ThreadCopies& copies) const {
    (void)copies;
    return nullptr;
  }

  virtual int inputSize() const = 0;
  virtual int outputSize() const = 0;

  virtual void evaluate(const double* z, double* y) const = 0;

  /// Pattern of dF/dz (row = output, col = input).
  virtual const SparsityPattern& jacobianPattern() const = 0;
  virtual void evaluateJacobian(const double* z, double* values) const = 0;

  /// Pattern of the lower triangle (row >= col) of sum_i w_i * Hessian(F_i).
  virtual const SparsityPattern& hessianPattern() const = 0;
  virtual void evaluateHessian(const double* z, const double* weights, double* values) const = 0;
};

}  // namespace fesd
