#pragma once

#include <memory>

#include <Eigen/Dense>

#include "fesd_trajopt/model/dcs_model.h"

namespace fesd {

/// Pozharskiy et al. 2024, Example 1: xdot = (x2, -x1 + lambda), 0 <= x2 + 1 _|_ lambda >= 0, from
/// x(0) = (sqrt 2, sqrt 2). A circle of radius 2 until contact at 5 pi / 12, sliding along
/// x2 = -1 until release at 5 pi / 12 + sqrt 3, then a circle of radius 1.
namespace circle_example {

std::shared_ptr<const DcsModel> model();  ///< analytic (affine) derivatives

/// The same system written as a user would for automatic differentiation.
struct Dynamics {
  template <class T>
  void operator()(const T* x, const T*, T* f) const {
    f[0] = x[1];
    f[1] = -x[0];
  }
};
struct Constraint {
  template <class T>
  void operator()(const T* x, T* c) const {
    c[0] = x[1] + 1.0;
  }
};
std::shared_ptr<const DcsModel> autodiffModel();  ///< Dynamics and Constraint through AD
Eigen::Vector2d initialState();
double horizon();                      ///< T = 11 pi / 12 + sqrt 3
double contactTime();                  ///< 5 pi / 12
double releaseTime();                  ///< 5 pi / 12 + sqrt 3
Eigen::Vector2d exactState(double t);  ///< x(T) = (-1, 0)

}  // namespace circle_example
}  // namespace fesd
