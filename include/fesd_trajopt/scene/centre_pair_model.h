#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/model/dcs_model.h"
#include "fesd_trajopt/scene/collision_centres.h"

namespace fesd {

/// One contact constraint between collision centres (CentreEvaluator):
///   kCentre: c = |p_a(x) - p_b(x)|^2 - constant,  constant = (r_a + r_b)^2
///   kPoint:  c = |p_a(x) - point|^2 - constant,   a fixed obstacle at `point`
///   kWall:   c = point . p_a(x) - constant,        point the unit normal, constant = offset + r_a
struct CentrePair {
  enum class Kind { kCentre, kPoint, kWall };
  Kind kind;
  CollisionCentre a, b;  ///< b only for kCentre
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  double constant = 0.0;
};

/// The value of one pair's constraint at x.
double centrePairValue(const CentreEvaluator& evaluator, const CentrePair& pair);

/// What the DCS of centre pairs is made of: x holds the free bodies and the robot's q (first),
/// u the velocity commands, each driving one state coordinate (f(x, u) = B u).
struct CentrePairSystem {
  std::shared_ptr<const KinematicModel> robot;  ///< may be null
  int dimension = 2;
  int state_size = 0, control_size = 0;
  std::vector<std::pair<int, int>> actuation;  ///< (state index, control index)
  std::vector<CentrePair> pairs;
  Eigen::VectorXd constraint_scales;  ///< per pair, see DcsModel
  /// Per state coordinate (empty: all 1): the share of the contacts' forces it moves by, the
  /// inverse of its weight in the projection's metric: v_i = f_i + mobility_i sum_k lambda_k
  /// dc_k/dx_i. 0 holds the coordinate (a support holds a body's height): its command is dropped
  /// too, its velocity 0.
  std::vector<double> mobility;
};

/// The DCS xdot = B u + diag(mobility) grad c(x) lambda, 0 <= c(x) _|_ lambda >= 0 of centre pairs
/// with exact sparse derivatives (the held coordinates' rows zero, left out of the patterns).
/// Unlike the disc scenes' quadratic c, a robot sphere's c(q) has curvature of every order, so the
/// velocity's Jacobian holds lambda_k Hess c_k and the Hessian of w . v the third derivatives of
/// c_k (contracted with w) and the mixed terms Hess c_k w.
std::shared_ptr<const DcsModel> centrePairModel(const CentrePairSystem& system,
                                                const std::string& name);

/// Per held coordinate i (mobility 0) with a direction s_i: the rate s_i sum_k lambda_k dc_k/dx_i
/// at which the contacts' forces would move it were it free (mobility 1), on (x, u, lambda) as
/// the model's velocity, with the same exact sparse derivatives. A support holds a body's height
/// by pushing only: its rate along the support's normal must stay <= 0.
std::shared_ptr<const SmoothFunction> heldCoordinateRates(
    const CentrePairSystem& system, const std::vector<std::pair<int, double>>& held);

}  // namespace fesd
