#pragma once

#include <memory>
#include <vector>

#include "fesd_trajopt/function/smooth_function.h"

namespace fesd {

/// One output row of a function F at a linear combination of points, y = F_row(sum_b w_b x_b):
/// e.g. a constraint on an element's collocation polynomial between its stage points (the
/// polynomial at a fixed fraction of the element is such a combination of the element's start
/// and stage states, whatever the element's length). Its input is, per point b in turn, the
/// coordinates of F's input that the row depends on (its Jacobian pattern's columns, in
/// increasing order); the other coordinates of F's input are held at zero.
class CombinationRow : public SmoothFunction {
 public:
  CombinationRow(std::shared_ptr<const SmoothFunction> function, int row,
                 std::vector<double> weights);

  /// The coordinates of F's input the row depends on: per point, these make up the input.
  const std::vector<int>& coordinates() const { return coordinates_; }

  int inputSize() const override { return static_cast<int>(weights_.size() * coordinates_.size()); }
  int outputSize() const override { return 1; }
  void evaluate(const double* z, double* y) const override;
  const SparsityPattern& jacobianPattern() const override { return jacobian_pattern_; }
  void evaluateJacobian(const double* z, double* values) const override;
  const SparsityPattern& hessianPattern() const override { return hessian_pattern_; }
  void evaluateHessian(const double* z, const double* weights, double* values) const override;
  std::shared_ptr<const SmoothFunction> threadCopy(ThreadCopies& copies) const override;

 private:
  /// F's input at the combination of the points in z.
  std::vector<double> combined(const double* z) const;

  std::shared_ptr<const SmoothFunction> function_;
  int row_;
  std::vector<double> weights_;
  std::vector<int> coordinates_;
  std::vector<int> row_entries_;  ///< F's Jacobian entries of the row, in coordinates_ order
  SparsityPattern jacobian_pattern_, hessian_pattern_;
  /// Per entry of hessian_pattern_: F's Hessian entry and the product of the two weights.
  std::vector<int> hessian_sources_;
  std::vector<double> hessian_factors_;
};

}  // namespace fesd
