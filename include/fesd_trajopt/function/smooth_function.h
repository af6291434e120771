#pragma once

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

/// A twice continuously differentiable map y = F(z) on a small argument, with exact sparse
/// derivatives. Everything the discretised problem evaluates (the DCS velocity, the constraint
/// functions, costs, path constraints) is one of these, evaluated at many points.
class SmoothFunction {
 public:
  virtual ~SmoothFunction() = default;

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
