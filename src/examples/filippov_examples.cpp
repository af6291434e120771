#include "fesd_trajopt/examples/filippov_examples.h"

#include <cmath>

#include <Eigen/Geometry>

#include "fesd_trajopt/discretization/stewart_discretization.h"
#include "fesd_trajopt/function/quadratic_function.h"

namespace fesd {
namespace spiral_example {
namespace {

constexpr double kOmega = 2.0 * M_PI;

/// Mode 0: c > 0 (outside, A2 x); mode 1: c < 0 (inside, A1 x): the rows of signMatrix(1).
struct Modes {
  template <class T>
  void operator()(const T* x, const T*, T* F) const {
    F[0] = x[0] - kOmega * x[1];
    F[1] = kOmega * x[0] + x[1];
    F[2] = x[0] + kOmega * x[1];
    F[3] = -kOmega * x[0] + x[1];
  }
};
struct Circle {
  template <class T>
  void operator()(const T* x, T* c) const {
    c[0] = x[0] * x[0] + x[1] * x[1] - 1.0;
  }
};

}  // namespace

std::shared_ptr<const StewartModel> model() {
  static const auto instance = makeSwitchingModel(2, 0, {1}, Modes{}, Circle{}, "spiral");
  return instance;
}

Eigen::Vector2d initialState() {
  return {std::exp(-1.0), 0.0};
}
double horizon() {
  return M_PI / 2.0;
}
double switchTime() {
  return 1.0;
}

Eigen::Vector2d exactState(double t) {
  // Inside, z = x1 + i x2 follows z' = (1 - i w) z and reaches (1, 0) at t = 1 after one full
  // turn; outside z' = (1 + i w) z.
  return std::exp(t - 1.0) *
         Eigen::Vector2d(std::cos(kOmega * (t - 1.0)), std::sin(kOmega * (t - 1.0)));
}

Eigen::Matrix2d exactSensitivity(const Eigen::Vector2d& x0, double t) {
  const auto flow = [](double time, double angular) {
    return Eigen::Matrix2d(std::exp(time) * Eigen::Rotation2Dd(angular * time).toRotationMatrix());
  };
  const double t_switch = -std::log(x0.norm());
  const Eigen::Vector2d x_switch = flow(t_switch, -kOmega) * x0;
  Eigen::Matrix2d inside, outside;
  inside << 1.0, kOmega, -kOmega, 1.0;
  outside << 1.0, -kOmega, kOmega, 1.0;
  const Eigen::Vector2d f1 = inside * x_switch, f2 = outside * x_switch, n = 2.0 * x_switch;
  const Eigen::Matrix2d saltation =
      Eigen::Matrix2d::Identity() + (f2 - f1) * n.transpose() / n.dot(f1);
  return flow(t - t_switch, kOmega) * saltation * flow(t_switch, -kOmega);
}

}  // namespace spiral_example

namespace sign_example {
namespace {

/// Mode 0: x > 0, xdot = 1; mode 1: x < 0, xdot = 3.
struct Modes {
  template <class T>
  void operator()(const T*, const T*, T* F) const {
    F[0] = T(1.0);
    F[1] = T(3.0);
  }
};
struct Identity {
  template <class T>
  void operator()(const T* x, T* c) const {
    c[0] = x[0];
  }
};

}  // namespace

std::shared_ptr<const StewartModel> model() {
  static const auto instance = makeSwitchingModel(1, 0, {1}, Modes{}, Identity{}, "two_minus_sign");
  return instance;
}

double exactState(double x0, double t) {
  return x0 >= 0.0 ? x0 + t : t + x0 / 3.0;
}

double exactSensitivity(double x0) {
  return x0 >= 0.0 ? 1.0 : 1.0 / 3.0;
}

double optimalInitialState() {
  return -(std::sqrt(417.0) - 9.0) / 8.0;
}

OcpDefinition ocp(double x0_guess) {
  OcpDefinition ocp;
  ocp.model = model();
  ocp.initial_state = Eigen::VectorXd::Constant(1, x0_guess);
  ocp.initial_state_lower = Eigen::VectorXd::Constant(1, -3.0);
  ocp.initial_state_upper = Eigen::VectorXd::Constant(1, 3.0);
  ocp.horizon = 2.0;
  ocp.num_intervals = 1;
  ocp.lagrange_cost =
      QuadraticFunction::weightedDistance(Eigen::VectorXd::Ones(1), Eigen::VectorXd::Zero(1));
  ocp.mayer_cost = QuadraticFunction::weightedDistance(Eigen::VectorXd::Ones(1),
                                                       Eigen::VectorXd::Constant(1, 5.0 / 3.0));
  return ocp;
}

DiscretizationOptions discretization(bool fesd) {
  DiscretizationOptions options;
  options.family = CollocationFamily::kGaussLegendre;
  options.num_stages = 2;
  options.num_elements = 25;
  options.switch_detection = fesd;
  return options;
}

Result solve(double x0_guess, bool fesd, const HomotopyOptions& homotopy) {
  StewartDiscretization discretization(ocp(x0_guess), sign_example::discretization(fesd));
  discretization.setInitialState(Eigen::VectorXd::Constant(1, x0_guess));
  MpccSolver simulation_solver;
  const MpccReport guess =
      simulation_solver.solve(discretization.nlp(), discretization.constantGuess());
  discretization.releaseInitialState();
  MpccSolver solver(homotopy);
  const MpccReport report = solver.solve(discretization.nlp(), guess.solution);
  return {guess.status, report.status, report.solution[discretization.startStateIndex()],
          report.objective};
}

}  // namespace sign_example

namespace sliding_example {
namespace {

/// Mode 0: x1 > 0, mode 1: x1 < 0.
struct Modes {
  template <class T>
  void operator()(const T*, const T*, T* F) const {
    F[0] = T(-0.5);
    F[1] = T(1.0);
    F[2] = T(1.5);
    F[3] = T(-1.0);
  }
};
struct FirstState {
  template <class T>
  void operator()(const T* x, T* c) const {
    c[0] = x[0];
  }
};

}  // namespace

std::shared_ptr<const StewartModel> model() {
  static const auto instance = makeSwitchingModel(2, 0, {1}, Modes{}, FirstState{}, "sliding");
  return instance;
}

Eigen::Vector2d initialState() {
  return {0.37, 0.2};
}

double horizon() {
  return 2.0;
}

}  // namespace sliding_example

namespace sliding_ocp_example {
namespace {

/// Subsystem k moves q_k: mode 0 (phi_k > 0) with -1, mode 1 (phi_k < 0) with +1. The drift
/// v and vdot = u are carried by subsystem 1's modes (theta^1 sums to one).
struct Modes {
  template <class T>
  void operator()(const T* x, const T* u, T* F) const {
    for (int i = 0; i < 16; ++i) F[i] = T(0.0);
    for (int mode = 0; mode < 2; ++mode) {
      T* column = F + 4 * mode;
      column[0] = x[2] + (mode == 0 ? -1.0 : 1.0);
      column[2] = u[0];
      column[3] = u[1];
      F[4 * (2 + mode) + 1] = x[3] + (mode == 0 ? -1.0 : 1.0);
    }
  }
};
struct Surfaces {
  template <class T>
  void operator()(const T* x, T* c) const {
    c[0] = x[0] + 0.15 * x[1] * x[1];
    c[1] = -0.05 * x[0] * x[0] * x[0] + x[1];
  }
};
/// q(T) - q_final <= 0 and q_final - q(T) <= 0.
struct TerminalPosition {
  template <class T>
  void operator()(const T* x, T* g) const {
    const Eigen::Vector2d target = targetPosition();
    for (int d = 0; d < 2; ++d) {
      g[d] = x[d] - target(d);
      g[2 + d] = target(d) - x[d];
    }
  }
};

}  // namespace

std::shared_ptr<const StewartModel> model() {
  static const auto instance =
      makeSwitchingModel(4, 2, {1, 1}, Modes{}, Surfaces{}, "two_sliding_surfaces");
  return instance;
}

Eigen::Vector2d targetPosition() {
  return {-M_PI / 6.0, -M_PI / 4.0};
}

OcpDefinition ocp() {
  OcpDefinition ocp;
  ocp.model = model();
  ocp.initial_state = Eigen::Vector4d(2.0 * M_PI / 3.0, M_PI / 3.0, 0.0, 0.0);
  ocp.horizon = 4.0;
  ocp.num_intervals = 6;
  const double inf = NlpAssembly::kInfinity;
  ocp.state_lower = Eigen::Vector4d(-inf, -inf, -2.0, -2.0);
  ocp.state_upper = Eigen::Vector4d(inf, inf, 2.0, 2.0);
  ocp.control_lower = Eigen::Vector2d::Constant(-10.0);
  ocp.control_upper = Eigen::Vector2d::Constant(10.0);
  Eigen::VectorXd weights(6);
  weights << 0.0, 0.0, 1.0, 1.0, 1.0, 1.0;  // |v|^2 + |u|^2 on (x, u)
  ocp.lagrange_cost = QuadraticFunction::weightedDistance(weights, Eigen::VectorXd::Zero(6));
  ocp.terminal_constraints = makeAutoDiffFunction(4, 4, TerminalPosition{});
  return ocp;
}

}  // namespace sliding_ocp_example
}  // namespace fesd
