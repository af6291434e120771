#pragma once

#include <memory>

#include <Eigen/Dense>

#include "fesd_trajopt/model/ocp_definition.h"
#include "fesd_trajopt/model/stewart_model.h"
#include "fesd_trajopt/solver/mpcc_solver.h"

namespace fesd {

/// Nurkanovic et al. 2024, example (47): xdot = A1 x inside the unit circle (c(x) = |x|^2 - 1 < 0),
/// A2 x outside, from x(0) = (1/e, 0): a spiral that crosses the circle at t = 1. Clockwise
/// rotation inside, anticlockwise outside, radius e^(t - 1) throughout.
namespace spiral_example {
std::shared_ptr<const StewartModel> model();
Eigen::Vector2d initialState();
double horizon();                      ///< T = pi / 2, so t = 1 is never an element boundary
double switchTime();                   ///< 1
Eigen::Vector2d exactState(double t);  ///< t >= 1
/// d x(t) / d x0 from x0 inside the circle, t after the crossing at -ln|x0|: the flows inside and
/// outside joined by the saltation matrix I + (f2 - f1) n^T / (n^T f1) (n = grad c).
Eigen::Matrix2d exactSensitivity(const Eigen::Vector2d& x0, double t);
}  // namespace spiral_example

/// Nurkanovic et al. 2024, OCP (56): min_{x0} int_0^2 x^2 dt + (x(2) - 5/3)^2, xdot in 2 - sign(x).
/// Only x0 is free; the reduced objective has its minimum at x0* = -(sqrt(417) - 9) / 8.
namespace sign_example {
std::shared_ptr<const StewartModel> model();
/// x(t) and d x(t) / d x0 of x' = 2 - sign(x) in closed form (t after any crossing).
double exactState(double x0, double t);
double exactSensitivity(double x0);
double optimalInitialState();
/// The OCP with a free start in [-3, 3], x0_guess as its guess.
OcpDefinition ocp(double x0_guess);
/// The grid of the paper's experiment: Gauss-Legendre, n_s = 2, 25 elements.
DiscretizationOptions discretization(bool fesd);

struct Result {
  SolveStatus guess_status;  ///< the forward simulation that gives the guess
  SolveStatus status;
  double initial_state;  ///< x0 found
  double objective;
};
/// The experiment of Nurkanovic et al. 2024 Sec. 4.6: a forward simulation from x0_guess with the
/// same method and grid is the guess; the OCP is then solved with the given homotopy (e.g. a single
/// relaxed NLP at a fixed sigma).
Result solve(double x0_guess, bool fesd, const HomotopyOptions& homotopy);
}  // namespace sign_example

/// A sliding mode (Nurkanovic et al. 2024, Sec. 4.5): x1' = 1/2 - sign(x1), x2' = sign(x1). From
/// x1(0) > 0, x1 reaches 0 at t* = 2 x1(0) and slides there (Filippov: the modes weighted 3/4 and
/// 1/4), x2' = 1/2 all along: x(T) = (0, x2(0) + x1(0) + T / 2) for T > t*.
namespace sliding_example {
std::shared_ptr<const StewartModel> model();
Eigen::Vector2d initialState();  ///< (0.37, 0.2)
double horizon();                ///< 2
}  // namespace sliding_example

/// Nurkanovic et al. 2024, OCP (61): x = (q, v) in R^4, qdot = -sign(c(q)) + v componentwise with
/// c = (phi1, phi2), phi1 = q1 + 0.15 q2^2, phi2 = -0.05 q1^3 + q2, vdot = u; two independent
/// subsystems (n_sys = 2). min int_0^4 |u|^2 + |v|^2 dt, |v| <= 2, |u| <= 10, reaching
/// q(4) = (-pi/6, -pi/4) (the terminal constraint that the paper's exact L1 penalty with
/// rho = 1e3 imposes) from x(0) = (2 pi / 3, pi / 3, 0, 0).
namespace sliding_ocp_example {
std::shared_ptr<const StewartModel> model();
Eigen::Vector2d targetPosition();
/// N_ctrl = 6 control intervals on [0, 4].
OcpDefinition ocp();
}  // namespace sliding_ocp_example

}  // namespace fesd
