#pragma once

#include <string>
#include <vector>

#include "fesd_trajopt/function/autodiff_function.h"
#include "fesd_trajopt/function/gradient_dual.h"
#include "fesd_trajopt/model/dcs_model.h"

namespace fesd {

namespace detail {

/// The DCS velocity v(z) = f(x, u) + grad c(x) lambda, z = (x, u, lambda), for any scalar T.
/// grad c is itself formed by one more forward-mode level over T (GradientDual), so the
/// velocity's Jacobian and Hessian (second and third derivatives of c) stay exact.
template <class Dynamics, class Constraints>
struct DcsVelocity {
  int nx, nu, nc;
  Dynamics dynamics;
  Constraints constraints;

  template <class T>
  void operator()(const T* z, T* v) const {
    const T* x = z;
    const T* u = z + nx;
    const T* lambda = z + nx + nu;
    dynamics(x, u, v);
    if (nc == 0) return;
    using Inner = GradientDual<T>;
    std::vector<Inner> xi(nx), ci(nc);
    for (int i = 0; i < nx; ++i) xi[i] = Inner::variable(x[i], nx, i);
    constraints(xi.data(), ci.data());
    for (int k = 0; k < nc; ++k) {
      const auto& gradient = ci[k].gradient();
      for (int i = 0; i < gradient.size(); ++i) v[i] += gradient(i) * lambda[k];
    }
  }
};

}  // namespace detail

/// Builds a DCS model from user functors, differentiated by Eigen's AutoDiff:
///   dynamics:    template <class T> void operator()(const T* x, const T* u, T* f) const;
///   constraints: template <class T> void operator()(const T* x, T* c) const;
template <class Dynamics, class Constraints>
DcsModel makeAutoDiffModel(int nx, int nu, int nc, Dynamics dynamics, Constraints constraints,
                           std::string name) {
  auto constraint_function =
      makeAutoDiffFunction(nx, nc, [constraints](const auto* x, auto* c) { constraints(x, c); });
  auto velocity = makeAutoDiffFunction(
      nx + nu + nc, nx,
      detail::DcsVelocity<Dynamics, Constraints>{nx, nu, nc, dynamics, constraints});
  return DcsModel(nx, nu, nc, velocity, constraint_function, std::move(name));
}

}  // namespace fesd
