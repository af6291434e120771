#pragma once

#include <cstdint>

// Column kernels for the short columns of KKT factors (tens of rows): plain loops over four
// columns at a time, where a dense-kernel call costs more than its arithmetic. The order of every
// sum is fixed, so results do not depend on how the compiler vectorises them.
namespace fesd::linalg::kernels {

/// target[i] -= sum_p columns[p][i] * weights[p], p < count, i < length; column p starts at
/// first + p * stride.
inline void subtractCombination(double* __restrict target, int length, const double* first,
                                int64_t stride, const double* weights, int count) {
  int p = 0;
  for (; p + 4 <= count; p += 4) {
    const double* a = first + p * stride;
    const double* b = a + stride;
    const double* c = b + stride;
    const double* d = c + stride;
    const double wa = weights[p], wb = weights[p + 1], wc = weights[p + 2], wd = weights[p + 3];
    for (int i = 0; i < length; ++i) target[i] -= (a[i] * wa + b[i] * wb) + (c[i] * wc + d[i] * wd);
  }
  for (; p < count; ++p) {
    const double* a = first + p * stride;
    const double w = weights[p];
    for (int i = 0; i < length; ++i) target[i] -= a[i] * w;
  }
}

/// sum_i a[i] b[i] in four interleaved partial sums, added in a fixed order.
inline double dot(const double* a, const double* b, int length) {
  double s0 = 0.0, s1 = 0.0, s2 = 0.0, s3 = 0.0;
  int i = 0;
  for (; i + 4 <= length; i += 4) {
    s0 += a[i] * b[i];
    s1 += a[i + 1] * b[i + 1];
    s2 += a[i + 2] * b[i + 2];
    s3 += a[i + 3] * b[i + 3];
  }
  for (; i < length; ++i) s0 += a[i] * b[i];
  return (s0 + s1) + (s2 + s3);
}

/// results[p] -= sum_i columns[p][i] * x[i], p < count, i < length; column p starts at
/// first + p * stride. Four columns share each pass over x.
inline void subtractProducts(double* results, int count, const double* first, int64_t stride,
                             const double* x, int length) {
  int p = 0;
  for (; p + 4 <= count; p += 4) {
    const double* a = first + p * stride;
    const double* b = a + stride;
    const double* c = b + stride;
    const double* d = c + stride;
    double sa = 0.0, sb = 0.0, sc = 0.0, sd = 0.0;
    for (int i = 0; i < length; ++i) {
      sa += a[i] * x[i];
      sb += b[i] * x[i];
      sc += c[i] * x[i];
      sd += d[i] * x[i];
    }
    results[p] -= sa;
    results[p + 1] -= sb;
    results[p + 2] -= sc;
    results[p + 3] -= sd;
  }
  for (; p < count; ++p) results[p] -= dot(first + p * stride, x, length);
}

}  // namespace fesd::linalg::kernels
