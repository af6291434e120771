// Ipopt's vector algebra (IpBlas) calls the level-1 BLAS for every inner product, norm and
// update of every iteration. Kernels differ in summation order and in fused multiply-adds, so
// the same solve took different iterations and ended at different points under reference BLAS,
// Prescott, Haswell and SkylakeX (the hard cases: 157 to 172 Ipopt iterations). libipopt calls
// them through its PLT, so the definitions below, in a fixed order (no fused multiply-adds:
// CMakeLists.txt),
// take their place in every process linking fesd_core: with our LDL^T (no BLAS) a solve is
// the same bit for bit under every BLAS. MUMPS's own level-3 kernels stay the installed BLAS's.
#include <algorithm>
#include <cmath>

#include "../linalg/column_kernels.h"

namespace {

/// The BLAS convention: a negative increment walks the vector backwards from its end.
inline long firstIndex(int n, int increment) {
  return increment < 0 ? static_cast<long>(1 - n) * increment : 0;
}

}  // namespace

extern "C" {

double ddot_(const int* n, const double* x, const int* incx, const double* y, const int* incy) {
  if (*n <= 0) return 0.0;
  if (*incx == 1 && *incy == 1) return fesd::linalg::kernels::dot(x, y, *n);
  double sum = 0.0;
  for (long i = 0, ix = firstIndex(*n, *incx), iy = firstIndex(*n, *incy); i < *n;
       ++i, ix += *incx, iy += *incy) {
    sum += x[ix] * y[iy];
  }
  return sum;
}

void daxpy_(const int* n, const double* alpha, const double* x, const int* incx, double* y,
            const int* incy) {
  if (*n <= 0 || *alpha == 0.0) return;
  for (long i = 0, ix = firstIndex(*n, *incx), iy = firstIndex(*n, *incy); i < *n;
       ++i, ix += *incx, iy += *incy) {
    y[iy] += *alpha * x[ix];
  }
}

double dasum_(const int* n, const double* x, const int* incx) {
  if (*n <= 0 || *incx <= 0) return 0.0;
  double sum = 0.0;
  for (long i = 0, ix = 0; i < *n; ++i, ix += *incx) sum += std::fabs(x[ix]);
  return sum;
}

/// Scaled by the largest magnitude, so that squares neither overflow nor underflow.
double dnrm2_(const int* n, const double* x, const int* incx) {
  if (*n <= 0 || *incx <= 0) return 0.0;
  double scale = 0.0;
  for (long i = 0, ix = 0; i < *n; ++i, ix += *incx) scale = std::max(scale, std::fabs(x[ix]));
  if (scale == 0.0 || !std::isfinite(scale)) return scale;
  double sum = 0.0;
  for (long i = 0, ix = 0; i < *n; ++i, ix += *incx) {
    const double scaled = x[ix] / scale;
    sum += scaled * scaled;
  }
  return scale * std::sqrt(sum);
}

}  // extern "C"
