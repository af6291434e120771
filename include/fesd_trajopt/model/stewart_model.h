#pragma once

#include <memory>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/function/autodiff_function.h"
#include "fesd_trajopt/function/smooth_function.h"
#include "fesd_trajopt/model/dynamics_model.h"

namespace fesd {

/// A Filippov system in Stewart's form (Nurkanovic et al. 2024, eq. 8), possibly a Cartesian
/// product of n_sys independent subsystems (eq. 21):
///   xdot = sum_k F^k(x, u) theta^k,   0 = g^k(x) - lambda^k - mu^k e,   1 = e^T theta^k,
///   0 <= theta^k  _|_  lambda^k >= 0,   k = 1..n_sys.
/// theta, lambda and g stack the subsystems' modes (n_f = sum_k n_f^k modes in all). Given by
/// two smooth functions: the velocity v(x, u, theta) = F(x, u) theta on z = (x, u, theta), and
/// the indicator functions g(x) in R^{n_f}.
class StewartModel : public DynamicsModel {
 public:
  StewartModel(int state_size, int control_size, std::vector<int> modes_per_subsystem,
               std::shared_ptr<const SmoothFunction> velocity,
               std::shared_ptr<const SmoothFunction> indicators, std::string name);

  int stateSize() const override { return state_size_; }
  int controlSize() const override { return control_size_; }
  const std::string& name() const override { return name_; }
  /// A StewartDiscretization.
  std::unique_ptr<Discretization> discretize(const OcpDefinition& ocp,
                                             const DiscretizationOptions& options) const override;

  int numModes() const { return static_cast<int>(subsystem_of_mode_.size()); }  ///< n_f
  int numSubsystems() const { return static_cast<int>(modes_per_subsystem_.size()); }
  const std::vector<int>& modesPerSubsystem() const { return modes_per_subsystem_; }
  int subsystemOf(int mode) const { return subsystem_of_mode_[mode]; }

  const std::shared_ptr<const SmoothFunction>& velocity() const { return velocity_; }
  const std::shared_ptr<const SmoothFunction>& indicators() const { return indicators_; }

  /// mu^k = min_i g^k_i(x) and lambda = g(x) - mu^k e: the multipliers of Stewart's LP at x.
  void lpMultipliers(const double* x, double* lambda, double* mu) const;

 private:
  int state_size_, control_size_;
  std::vector<int> modes_per_subsystem_, subsystem_of_mode_;
  std::shared_ptr<const SmoothFunction> velocity_, indicators_;
  std::string name_;
};

/// The sign matrix S in {-1, 1}^(2^m x m) of m switching functions (Nurkanovic et al. 2024,
/// Sec. 2.2.1): row i is the sign pattern of region i; row 0 is all +1, the last column alternates
/// fastest.
Eigen::MatrixXd signMatrix(int switching_functions);

namespace detail {

/// v = F(x, u) theta on z = (x, u, theta); `modes` writes F column by column.
template <class Modes>
struct StewartVelocity {
  int nx, nu, nf;
  Modes modes;

  template <class T>
  void operator()(const T* z, T* v) const {
    std::vector<T> columns(nx * nf);
    modes(z, z + nx, columns.data());
    const T* theta = z + nx + nu;
    for (int d = 0; d < nx; ++d) v[d] = columns[d] * theta[0];
    for (int i = 1; i < nf; ++i) {
      for (int d = 0; d < nx; ++d) v[d] += columns[i * nx + d] * theta[i];
    }
  }
};

/// g^k(x) = -S^k c^k(x) for every subsystem k, from all switching functions c(x) stacked.
template <class Switching>
struct SignedIndicators {
  std::vector<Eigen::MatrixXd> signs;  ///< S^k per subsystem
  int total_switching;
  Switching switching;

  template <class T>
  void operator()(const T* x, T* g) const {
    std::vector<T> c(total_switching);
    switching(x, c.data());
    int first_c = 0, mode = 0;
    for (const Eigen::MatrixXd& sign : signs) {
      for (int i = 0; i < sign.rows(); ++i, ++mode) {
        g[mode] = -sign(i, 0) * c[first_c];
        for (int j = 1; j < sign.cols(); ++j) g[mode] -= sign(i, j) * c[first_c + j];
      }
      first_c += static_cast<int>(sign.cols());
    }
  }
};

}  // namespace detail

/// A Stewart model from user functors, differentiated by Eigen's AutoDiff:
///   modes:      template <class T> void operator()(const T* x, const T* u, T* F) const;
///               writes the n_x x n_f matrix [F^1 ... F^n_sys] column by column
///               (F[i * n_x + d] is component d of mode i);
///   indicators: template <class T> void operator()(const T* x, T* g) const;  g in R^{n_f}.
template <class Modes, class Indicators>
std::shared_ptr<const StewartModel> makeStewartModel(int nx, int nu,
                                                     std::vector<int> modes_per_subsystem,
                                                     Modes modes, Indicators indicators,
                                                     std::string name) {
  int nf = 0;
  for (int n : modes_per_subsystem) nf += n;
  auto velocity =
      makeAutoDiffFunction(nx + nu + nf, nx, detail::StewartVelocity<Modes>{nx, nu, nf, modes});
  auto indicator_function =
      makeAutoDiffFunction(nx, nf, [indicators](const auto* x, auto* g) { indicators(x, g); });
  return std::make_shared<StewartModel>(nx, nu, std::move(modes_per_subsystem), velocity,
                                        indicator_function, std::move(name));
}

/// A Stewart model whose regions are given by switching functions (Nurkanovic et al. 2024,
/// Sec. 2.2.1, 2.3): subsystem k has m_k switching functions c^k(x) and 2^m_k modes, mode i being
/// the region with the signs of row i of signMatrix(m_k); its indicators are g^k = -S^k c^k.
///   switching: template <class T> void operator()(const T* x, T* c) const;  c = (c^1, ...).
template <class Modes, class Switching>
std::shared_ptr<const StewartModel> makeSwitchingModel(int nx, int nu,
                                                       std::vector<int> switching_per_subsystem,
                                                       Modes modes, Switching switching,
                                                       std::string name) {
  std::vector<int> modes_per_subsystem;
  std::vector<Eigen::MatrixXd> signs;
  int total_switching = 0;
  for (int m : switching_per_subsystem) {
    signs.push_back(signMatrix(m));
    modes_per_subsystem.push_back(static_cast<int>(signs.back().rows()));
    total_switching += m;
  }
  return makeStewartModel(
      nx, nu, std::move(modes_per_subsystem), std::move(modes),
      detail::SignedIndicators<Switching>{std::move(signs), total_switching, switching},
      std::move(name));
}

}  // namespace fesd
