#include "fesd_trajopt/examples/circle_example.h"

#include <cmath>

#include "fesd_trajopt/function/affine_function.h"
#include "fesd_trajopt/model/autodiff_model.h"

namespace fesd {
namespace circle_example {

std::shared_ptr<const DcsModel> model() {
  // velocity on z = (x1, x2, lambda): (x2, -x1 + lambda); constraint c(x) = x2 + 1.
  Eigen::SparseMatrix<double> velocity(2, 3), constraint(1, 2);
  velocity.insert(0, 1) = 1.0;
  velocity.insert(1, 0) = -1.0;
  velocity.insert(1, 2) = 1.0;
  constraint.insert(0, 1) = 1.0;
  return std::make_shared<DcsModel>(
      2, 0, 1, std::make_shared<AffineFunction>(velocity, Eigen::Vector2d::Zero()),
      std::make_shared<AffineFunction>(constraint, Eigen::VectorXd::Ones(1)), "circle_example");
}

std::shared_ptr<const DcsModel> autodiffModel() {
  return std::make_shared<DcsModel>(
      makeAutoDiffModel(2, 0, 1, Dynamics{}, Constraint{}, "circle_example_autodiff"));
}

Eigen::Vector2d initialState() {
  return Eigen::Vector2d(std::sqrt(2.0), std::sqrt(2.0));
}
double horizon() {
  return 11.0 * M_PI / 12.0 + std::sqrt(3.0);
}
double contactTime() {
  return 5.0 * M_PI / 12.0;
}
double releaseTime() {
  return contactTime() + std::sqrt(3.0);
}

Eigen::Vector2d exactState(double t) {
  if (t < contactTime())
    return 2.0 * Eigen::Vector2d(std::sin(t + M_PI / 4), std::cos(t + M_PI / 4));
  if (t < releaseTime()) return Eigen::Vector2d(std::sqrt(3.0) - (t - contactTime()), -1.0);
  const double tau = t - releaseTime();
  return Eigen::Vector2d(-std::sin(tau), -std::cos(tau));
}

}  // namespace circle_example
}  // namespace fesd
