// Ipopt's level-1 BLAS replaced (solver/ipopt_blas.cpp): libipopt's calls resolve to ours, and
// ours compute what the BLAS specifies, increments and extreme magnitudes included.
#include <dlfcn.h>

#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

extern "C" {
double ddot_(const int* n, const double* x, const int* incx, const double* y, const int* incy);
void daxpy_(const int* n, const double* alpha, const double* x, const int* incx, double* y,
            const int* incy);
double dasum_(const int* n, const double* x, const int* incx);
double dnrm2_(const int* n, const double* x, const int* incx);
}

namespace {

TEST(IpoptBlas, LibipoptCallsOurs) {
  for (const char* name : {"ddot_", "daxpy_", "dasum_", "dnrm2_"}) {
    Dl_info where{};
    ASSERT_NE(dladdr(dlsym(RTLD_DEFAULT, name), &where), 0) << name;
    EXPECT_NE(std::string(where.dli_fname).find("fesd_core"), std::string::npos)
        << name << " resolves to " << where.dli_fname;
  }
}

TEST(IpoptBlas, DotProductWithAnyIncrements) {
  std::vector<double> x(11), y(22);
  for (int i = 0; i < 11; ++i) x[i] = 0.5 + i;
  for (int i = 0; i < 22; ++i) y[i] = 1.0 - 0.25 * i;
  const int n = 11, one = 1, two = 2, minus_two = -2;
  double unit = 0.0, strided = 0.0, backwards = 0.0;
  for (int i = 0; i < n; ++i) {
    unit += x[i] * y[i];
    strided += x[i] * y[2 * i];
    backwards += x[i] * y[2 * (n - 1 - i)];
  }
  EXPECT_DOUBLE_EQ(ddot_(&n, x.data(), &one, y.data(), &one), unit);
  EXPECT_DOUBLE_EQ(ddot_(&n, x.data(), &one, y.data(), &two), strided);
  EXPECT_DOUBLE_EQ(ddot_(&n, x.data(), &one, y.data(), &minus_two), backwards);
  const int none = 0;
  EXPECT_EQ(ddot_(&none, x.data(), &one, y.data(), &one), 0.0);
}

TEST(IpoptBlas, AxpyUpdatesOnlyTheStridedEntries) {
  const std::vector<double> x = {1.0, 2.0, 3.0};
  std::vector<double> y = {10.0, 20.0, 30.0, 40.0, 50.0, 60.0};
  const int n = 3, one = 1, minus_two = -2;
  const double alpha = 0.5;
  daxpy_(&n, &alpha, x.data(), &one, y.data(), &minus_two);  // y[4], y[2], y[0] += alpha x
  EXPECT_EQ(y, (std::vector<double>{11.5, 20.0, 31.0, 40.0, 50.5, 60.0}));
}

TEST(IpoptBlas, NormsOfExtremeMagnitudes) {
  const int n = 3, one = 1, two = 2;
  for (const double scale : {1e-300, 1.0, 1e300}) {
    const std::vector<double> x = {3.0 * scale, -4.0 * scale, 12.0 * scale};
    EXPECT_NEAR(dnrm2_(&n, x.data(), &one) / scale, 13.0, 1e-14) << scale;
    EXPECT_NEAR(dasum_(&n, x.data(), &one) / scale, 19.0, 1e-14) << scale;
  }
  const std::vector<double> strided = {3.0, 99.0, 4.0, 99.0};
  const int m = 2;
  EXPECT_DOUBLE_EQ(dnrm2_(&m, strided.data(), &two), 5.0);
  const std::vector<double> infinite = {1.0, INFINITY, 2.0};
  EXPECT_EQ(dnrm2_(&n, infinite.data(), &one), INFINITY);
  const std::vector<double> zero(3, 0.0);
  EXPECT_EQ(dnrm2_(&n, zero.data(), &one), 0.0);
}

}  // namespace
