#include "fesd_trajopt/function/smooth_function.h"

namespace fesd {

SparsityPattern SparsityPattern::dense(int num_rows, int num_cols, bool lower_triangle) {
  SparsityPattern pattern;
  for (int r = 0; r < num_rows; ++r) {
    for (int c = 0; c < (lower_triangle ? r + 1 : num_cols); ++c) pattern.add(r, c);
  }
  return pattern;
}

std::shared_ptr<const SmoothFunction> ThreadCopies::function(
    const std::shared_ptr<const SmoothFunction>& f) {
  const std::shared_ptr<const SmoothFunction> copy =
      of<SmoothFunction>(f.get(), [&] { return f->threadCopy(*this); });
  return copy ? copy : f;
}

}  // namespace fesd
