#include "fesd_trajopt/function/combination_row.h"

#include <algorithm>
#include <map>
#include <stdexcept>
#include <utility>

namespace fesd {

CombinationRow::CombinationRow(std::shared_ptr<const SmoothFunction> function, int row,
                               std::vector<double> weights)
    : function_(std::move(function)), row_(row), weights_(std::move(weights)) {
  if (!function_ || row_ < 0 || row_ >= function_->outputSize() || weights_.empty()) {
    throw std::invalid_argument("CombinationRow: no function, no such row or no point");
  }
  const SparsityPattern& jacobian = function_->jacobianPattern();
  std::map<int, int> entry_of;  // F's input coordinate -> its Jacobian entry in the row
  for (int i = 0; i < jacobian.nonzeros(); ++i) {
    if (jacobian.rows[i] == row_) entry_of[jacobian.cols[i]] = i;
  }
  for (const auto& [coordinate, entry] : entry_of) {
    coordinates_.push_back(coordinate);
    row_entries_.push_back(entry);
  }
  const int m = static_cast<int>(coordinates_.size());
  const int points = static_cast<int>(weights_.size());
  for (int b = 0; b < points; ++b) {
    for (int i = 0; i < m; ++i) jacobian_pattern_.add(0, b * m + i);
  }
  std::map<int, int> local;  // F's input coordinate -> its place among coordinates_
  for (int i = 0; i < m; ++i) local[coordinates_[i]] = i;
  // The Hessian of the row in z is W (x) H: (b, i), (c, j) -> w_b w_c H_ij, H symmetric, of
  // which F's pattern holds the lower triangle; entries outside the row's coordinates belong to
  // other rows.
  const SparsityPattern& hessian = function_->hessianPattern();
  for (int entry = 0; entry < hessian.nonzeros(); ++entry) {
    const auto a = local.find(hessian.rows[entry]), c = local.find(hessian.cols[entry]);
    if (a == local.end() || c == local.end()) continue;
    const std::pair<int, int> orders[] = {{a->second, c->second}, {c->second, a->second}};
    for (int order = 0; order < (a->second == c->second ? 1 : 2); ++order) {
      const auto [i, j] = orders[order];
      for (int b = 0; b < points; ++b) {
        for (int d = 0; d < points; ++d) {
          const int row = b * m + i, col = d * m + j;
          if (row < col) continue;
          hessian_pattern_.add(row, col);
          hessian_sources_.push_back(entry);
          hessian_factors_.push_back(weights_[b] * weights_[d]);
        }
      }
    }
  }
}

std::shared_ptr<const SmoothFunction> CombinationRow::threadCopy(ThreadCopies& copies) const {
  const std::shared_ptr<const SmoothFunction> function = copies.function(function_);
  if (function == function_) return nullptr;
  auto copy = std::make_shared<CombinationRow>(*this);
  copy->function_ = function;
  return copy;
}

std::vector<double> CombinationRow::combined(const double* z) const {
  std::vector<double> x(function_->inputSize(), 0.0);
  const size_t m = coordinates_.size();
  for (size_t b = 0; b < weights_.size(); ++b) {
    for (size_t i = 0; i < m; ++i) x[coordinates_[i]] += weights_[b] * z[b * m + i];
  }
  return x;
}

void CombinationRow::evaluate(const double* z, double* y) const {
  std::vector<double> values(function_->outputSize());
  function_->evaluate(combined(z).data(), values.data());
  y[0] = values[row_];
}

void CombinationRow::evaluateJacobian(const double* z, double* values) const {
  std::vector<double> jacobian(function_->jacobianPattern().nonzeros());
  function_->evaluateJacobian(combined(z).data(), jacobian.data());
  const size_t m = coordinates_.size();
  for (size_t b = 0; b < weights_.size(); ++b) {
    for (size_t i = 0; i < m; ++i) values[b * m + i] = weights_[b] * jacobian[row_entries_[i]];
  }
}

void CombinationRow::evaluateHessian(const double* z, const double* weights, double* values) const {
  std::vector<double> row_weight(function_->outputSize(), 0.0);
  row_weight[row_] = weights[0];
  std::vector<double> hessian(function_->hessianPattern().nonzeros());
  function_->evaluateHessian(combined(z).data(), row_weight.data(), hessian.data());
  for (size_t k = 0; k < hessian_sources_.size(); ++k) {
    values[k] = hessian_factors_[k] * hessian[hessian_sources_[k]];
  }
}

}  // namespace fesd
