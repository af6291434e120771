#pragma once

#include <cmath>
#include <memory>

#include "fesd_trajopt/model/dcs_model.h"

namespace fesd_test {

/// A nonlinear DCS whose constraint has nonzero third derivatives, so the velocity's Hessian
/// (which contains them) is exercised: x in R^3, u in R^2, two constraints.
struct BeadDynamics {
  template <class T>
  void operator()(const T* x, const T* u, T* f) const {
    using std::cos;
    using std::exp;
    using std::sin;
    f[0] = u[0] * cos(x[2]) + x[1] * x[0] * x[0];
    f[1] = sin(x[0]) * u[1];
    f[2] = x[0] * x[1] - exp(0.1 * x[2]) + u[0] * u[1];
  }
};
struct BeadConstraints {
  template <class T>
  void operator()(const T* x, T* c) const {
    using std::exp;
    using std::sin;
    c[0] = 1.0 - x[0] * x[0] - x[1] * x[1] - 0.5 * sin(x[2]) * sin(x[2]);
    c[1] = exp(0.2 * x[0]) * x[1] + 0.3 * x[2] * x[2] * x[2];
  }
};

/// The bead's DcsModel with derivatives by automatic differentiation (makeAutoDiffModel).
std::shared_ptr<const fesd::DcsModel> beadModel();

}  // namespace fesd_test
