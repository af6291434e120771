#include "fesd_trajopt/discretization/butcher_tableau.h"

#include <cmath>
#include <stdexcept>
#include <vector>

namespace fesd {
namespace {

using LongMatrix = Eigen::Matrix<long double, Eigen::Dynamic, Eigen::Dynamic>;
using LongVector = Eigen::Matrix<long double, Eigen::Dynamic, 1>;

/// Value and derivative of the shifted Legendre polynomial P_n(2t - 1) by its recurrence.
void shiftedLegendre(int n, long double t, long double* value, long double* derivative) {
  const long double x = 2.0L * t - 1.0L;
  long double p_prev = 1.0L, p = x, dp_prev = 0.0L, dp = 1.0L;
  if (n == 0) {
    *value = 1.0L;
    *derivative = 0.0L;
    return;
  }
  for (int k = 1; k < n; ++k) {
    const long double p_next = ((2.0L * k + 1.0L) * x * p - k * p_prev) / (k + 1.0L);
    const long double dp_next = dp_prev + (2.0L * k + 1.0L) * p;
    p_prev = p;
    p = p_next;
    dp_prev = dp;
    dp = dp_next;
  }
  *value = p;
  *derivative = 2.0L * dp;  // chain rule for x = 2t - 1
}

/// Collocation nodes: Gauss-Legendre are the roots of P_s(2t-1); Radau-IIA the roots of
/// P_s(2t-1) - P_{s-1}(2t-1), which include t = 1.
std::vector<long double> collocationNodes(CollocationFamily family, int stages) {
  auto residual = [&](long double t, long double* value, long double* derivative) {
    shiftedLegendre(stages, t, value, derivative);
    if (family == CollocationFamily::kRadauIIA) {
      long double v, d;
      shiftedLegendre(stages - 1, t, &v, &d);
      *value -= v;
      *derivative -= d;
    }
  };
  // The roots interlace with Chebyshev-like points; Newton from a fine bracketing scan.
  std::vector<long double> nodes;
  const int samples = 2000;
  long double t_prev = 0.0L, r_prev, d;
  residual(t_prev, &r_prev, &d);
  for (int k = 1; k <= samples; ++k) {
    const long double t = static_cast<long double>(k) / samples;
    long double r;
    residual(t, &r, &d);
    if (r == 0.0L || (r_prev != 0.0L && (r > 0) != (r_prev > 0))) {
      long double root = (r == 0.0L) ? t : 0.5L * (t + t_prev);
      for (int it = 0; it < 100; ++it) {
        long double value, slope;
        residual(root, &value, &slope);
        const long double step = value / slope;
        root -= step;
        if (std::fabs(step) < 1e-19L) break;
      }
      nodes.push_back(root);
    }
    t_prev = t;
    r_prev = r;
  }
  if (static_cast<int>(nodes.size()) != stages) {
    throw std::logic_error("collocation node search found the wrong number of roots");
  }
  if (family == CollocationFamily::kRadauIIA) nodes.back() = 1.0L;  // exact by construction
  return nodes;
}

}  // namespace

bool ButcherTableau::lastStageIsEndPoint() const {
  return c(stages - 1) == 1.0;
}

int ButcherTableau::order() const {
  return family == CollocationFamily::kRadauIIA ? 2 * stages - 1 : 2 * stages;
}

std::string ButcherTableau::name() const {
  return (family == CollocationFamily::kRadauIIA ? "radau_iia_" : "gauss_legendre_") +
         std::to_string(stages);
}

ButcherTableau makeTableau(CollocationFamily family, int stages) {
  if (stages < 1 || stages > 9) {
    throw std::invalid_argument("number of collocation stages must be in 1..9, got " +
                                std::to_string(stages));
  }
  const std::vector<long double> nodes = collocationNodes(family, stages);
  // C(s): sum_j a_ij c_j^(q-1) = c_i^q / q and B(s): sum_j b_j c_j^(q-1) = 1/q, q = 1..s.
  LongMatrix vandermonde(stages, stages);
  for (int q = 0; q < stages; ++q) {
    for (int j = 0; j < stages; ++j) vandermonde(q, j) = std::pow(nodes[j], q);
  }
  const Eigen::PartialPivLU<LongMatrix> lu(vandermonde);
  LongVector rhs_b(stages);
  for (int q = 0; q < stages; ++q) rhs_b(q) = 1.0L / (q + 1);
  const LongVector b = lu.solve(rhs_b);

  ButcherTableau tableau{family, stages, Eigen::MatrixXd(stages, stages), Eigen::VectorXd(stages),
                         Eigen::VectorXd(stages)};
  for (int i = 0; i < stages; ++i) {
    LongVector rhs(stages);
    for (int q = 0; q < stages; ++q) rhs(q) = std::pow(nodes[i], q + 1) / (q + 1);
    const LongVector row = lu.solve(rhs);
    for (int j = 0; j < stages; ++j) tableau.a(i, j) = static_cast<double>(row(j));
    tableau.b(i) = static_cast<double>(b(i));
    tableau.c(i) = static_cast<double>(nodes[i]);
  }
  return tableau;
}

}  // namespace fesd
