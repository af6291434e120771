#pragma once

#include <memory>
#include <string>

#include <Eigen/Dense>

#include "fesd_trajopt/function/smooth_function.h"
#include "fesd_trajopt/model/dynamics_model.h"

namespace fesd {

/// The dynamic complementarity system (DCS) of a projected dynamical system
///   xdot = f(x, u) + grad c(x) lambda,   0 <= c(x)  _|_  lambda >= 0,
/// given by two smooth functions:
///  - the velocity  v(x, u, lambda) = f(x, u) + grad c(x) lambda  on z = (x, u, lambda),
///  - the constraints  c(x)  on x.
/// The discretisation only ever evaluates these two, so a model may be analytic or built by
/// automatic differentiation (see autodiff_model.h).
class DcsModel : public DynamicsModel {
 public:
  /// `constraint_scales`: a typical |grad c_k| on the boundary c_k = 0, per constraint (empty:
  /// all 1). Active-set decisions compare c_k / scale (a distance to the boundary) with
  /// h lambda_k scale (the distance the force moves in a step h): one unit, whatever the
  /// model's. A disc pair's c = |p_i - p_j|^2 - R^2 has |grad c| = 2 R there.
  DcsModel(int state_size, int control_size, int constraint_size,
           std::shared_ptr<const SmoothFunction> velocity,
           std::shared_ptr<const SmoothFunction> constraints, std::string name,
           Eigen::VectorXd constraint_scales = {});

  int stateSize() const override { return state_size_; }
  int controlSize() const override { return control_size_; }
  int constraintSize() const { return constraint_size_; }
  const std::string& name() const override { return name_; }
  /// A PdsDiscretization.
  std::unique_ptr<Discretization> discretize(const OcpDefinition& ocp,
                                             const DiscretizationOptions& options) const override;

  const std::shared_ptr<const SmoothFunction>& velocity() const { return velocity_; }
  const std::shared_ptr<const SmoothFunction>& constraints() const { return constraints_; }
  const Eigen::VectorXd& constraintScales() const { return constraint_scales_; }

 private:
  int state_size_, control_size_, constraint_size_;
  std::shared_ptr<const SmoothFunction> velocity_, constraints_;
  std::string name_;
  Eigen::VectorXd constraint_scales_;
};

}  // namespace fesd
