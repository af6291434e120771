#pragma once

#include <cmath>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/scene/scene.h"

/// Shared tools of the numerical hard-case tests (regression/test_hard_cases_*.cpp) and the
/// push-scene sweep: small models, a simulation run twice to check determinism, and the checks
/// every case makes.
namespace hard_cases {

/// FESD with Radau-IIA: `stages` per element, `elements` per simulation step, step bound gamma_h.
fesd::SimulationOptions fesdOptions(int stages, int elements, double step_bound = 1.0);

/// fesdOptions with every step kept on `elements` elements (SimulationOptions::refine_elements
/// off): the discretisation of the papers, for tests of its own properties (orders, grid jumps).
fesd::SimulationOptions fixedElementCountOptions(int stages, int elements);

/// The affine DCS  xdot = F x + f0 + A^T lambda,  0 <= A x + b  _|_  lambda >= 0  (no controls).
std::shared_ptr<const fesd::DcsModel> affineModel(const Eigen::MatrixXd& F,
                                                  const Eigen::VectorXd& f0,
                                                  const Eigen::MatrixXd& A,
                                                  const Eigen::VectorXd& b);

/// A point (a body of radius 0) moving with a constant velocity u, i.e. the projected motion
/// of xdot = u among the scene's obstacles and walls; every obstacle and wall is a constraint.
struct PointScene {
  fesd::Scene scene{2};
  std::shared_ptr<const fesd::DcsModel> model() const;
};
PointScene pointScene(const Eigen::Vector2d& start);

/// A point moving with velocity (-1, -2) towards the floor x2 >= 0 (constraint 0) and the
/// oblique wall (x1 + x2) / sqrt 2 >= 0 (constraint 1) that meet at the origin at 135 degrees.
PointScene cornerScene(const Eigen::Vector2d& start);
const Eigen::Vector2d kCornerVelocity(-1.0, -2.0);

/// A point moving with velocity (v, 0) from (-2 R, R sin theta0) hits the disc |p| >= R at
/// polar angle theta0 in (pi / 2, pi), slides on it (R theta' = -v sin theta, so
/// tan(theta / 2) = tan(theta0 / 2) exp(-v (t - t_c) / R)) and is released at the top,
/// theta = pi / 2, where lambda = -v cos theta / (2 R) reaches 0 continuously; then a straight
/// line. Lengths scale with R and times with R / v.
struct DiscRelease {
  double radius = 1.0, speed = 1.0, theta0 = 5.0 * M_PI / 6.0;
  Eigen::Vector2d start() const;
  Eigen::Vector2d velocity() const { return {speed, 0.0}; }
  double contactTime() const;
  double releaseTime() const;
  double horizon() const { return 3.5 * radius / speed; }  ///< a straight piece after release
  Eigen::VectorXd exact(double t) const;
  std::shared_ptr<const fesd::DcsModel> model() const;
};

/// A simulation made twice by fresh integrators; `identical` says whether both runs gave
/// bitwise the same trajectory (times, states, stage values) and status.
struct CheckedRun {
  fesd::SimulationResult result;
  bool identical = false;
};
CheckedRun simulateTwice(std::shared_ptr<const fesd::DcsModel> model,
                         const fesd::SimulationOptions& options, const Eigen::VectorXd& x0,
                         double horizon, int steps,
                         const std::vector<Eigen::VectorXd>& controls = {});

/// Status kSuccess, complementarity residual <= `residual_bound`, every value finite, every
/// switch resolved by the grid, and both runs identical. Records the residual.
::testing::AssertionResult isHealthy(const CheckedRun& run, double residual_bound);

/// Records a number for the test report (XML output) with three significant digits.
void recordNumber(const std::string& key, double value);

/// Largest |x_n - x(t_n)| over the element boundaries t_n of a trajectory (Nurkanovic et al. 2024,
/// eq. 40b).
double maxGridError(const fesd::Trajectory& trajectory,
                    const std::function<Eigen::VectorXd(double)>& exact);

/// Largest lambda over all stage points of constraint k.
double maxMultiplier(const fesd::Trajectory& trajectory, int constraint);

/// The switches of one constraint, in time order.
std::vector<fesd::SwitchEvent> switchesOf(const fesd::Trajectory& trajectory, int constraint);

}  // namespace hard_cases
