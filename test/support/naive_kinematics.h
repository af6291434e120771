#pragma once

#include <Eigen/Dense>

#include "fesd_trajopt/kinematics/forward_kinematics.h"

namespace fesd_test {

// A sphere centre's second and third derivatives entry by entry, the formulas
// fesd::SphereDerivatives computes once per configuration (kinematics/sphere_derivatives.h):
// the reference its tests compare with and check against central differences. Joints off the
// sphere's chain give zero; the joint indices may come in any order.

/// d^2 p_s / dq_i dq_j.
Eigen::Vector3d sphereSecondDerivative(const fesd::KinematicModel& model,
                                       const fesd::KinematicData& data, int sphere, int i, int j);
/// d^3 p_s / dq_i dq_j dq_k.
Eigen::Vector3d sphereThirdDerivative(const fesd::KinematicModel& model,
                                      const fesd::KinematicData& data, int sphere, int i, int j,
                                      int k);
/// The nq x nq Hessian of w . p_s(q) for fixed w.
Eigen::MatrixXd weightedSphereHessian(const fesd::KinematicModel& model,
                                      const fesd::KinematicData& data, int sphere,
                                      const Eigen::Vector3d& w);
/// Its derivative along v (fixed w).
Eigen::MatrixXd weightedSphereThirdDerivative(const fesd::KinematicModel& model,
                                              const fesd::KinematicData& data, int sphere,
                                              const Eigen::Vector3d& w, const Eigen::VectorXd& v);

}  // namespace fesd_test
