// Hard case 9, continuity under perturbation: the PDS analogue of Nurkanovic et al. 2024, Example
// 5, where the FESD solution map is continuous in x0 except where a switch appears or disappears.
// xdot = -(1 + x^2) + lambda, 0 <= x _|_ lambda >= 0, one FESD step over T = 0.2 with N_FE = 2,
// Radau-IIA n_s = 2 (order 3, as in the paper). Exact: x(t) = tan(atan(x0) - t) until the
// contact at t_c = atan(x0), then x = 0. A contact happens within T for x0 < x0* = tan(T):
//  - the end state x(T) is continuous (Lipschitz with constant <= 1: the flow contracts);
//  - the element length h_0 follows t_c(x0) on the switch side and is T / 2 on the other, so
//    it jumps by about T / 2 at x0* (the discontinuity of Fig. 5 there).
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/model/autodiff_model.h"
#include "support/hard_cases.h"

namespace {

constexpr double kHorizon = 0.2;

struct Dynamics {
  template <class T>
  void operator()(const T* x, const T*, T* f) const {
    f[0] = -(1.0 + x[0] * x[0]);
  }
};
struct Floor {
  template <class T>
  void operator()(const T* x, T* c) const {
    c[0] = x[0];
  }
};

double exactEnd(double x0) {
  return std::max(std::tan(std::atan(x0) - kHorizon), 0.0);
}

struct Sample {
  double x0, end, first_step;
  bool has_switch;
};

TEST(HardCaseContinuity, EndStateIsContinuousAndTheGridJumpsOnlyWhereTheSwitchAppears) {
  const auto model = std::make_shared<fesd::DcsModel>(
      fesd::makeAutoDiffModel(1, 0, 1, Dynamics{}, Floor{}, "example5_pds"));
  const double threshold = std::tan(kHorizon);  // x0* = 0.2027...
  std::vector<double> starts;
  for (int i = 0; i <= 14; ++i) starts.push_back(0.05 + 0.025 * i);  // 0.05 ... 0.4
  for (double offset : {-1e-3, -1e-5, 1e-5, 1e-3}) starts.push_back(threshold + offset);
  std::sort(starts.begin(), starts.end());

  std::vector<Sample> samples;
  double worst_end_error = 0.0, worst_switch_time_error = 0.0;
  for (double x0 : starts) {
    const auto run = hard_cases::simulateTwice(model, hard_cases::fixedElementCountOptions(2, 2),
                                               Eigen::VectorXd::Constant(1, x0), kHorizon, 1);
    ASSERT_TRUE(hard_cases::isHealthy(run, 1e-9)) << "x0 = " << x0;
    const fesd::Trajectory& trajectory = run.result.trajectory;
    const Sample s{x0, trajectory.finalState()(0), trajectory.elements[0].step,
                   !trajectory.switches.empty()};
    EXPECT_EQ(s.has_switch, x0 < threshold) << "x0 = " << x0;
    worst_end_error = std::max(worst_end_error, std::fabs(s.end - exactEnd(x0)));
    if (s.has_switch) {
      EXPECT_NEAR(s.end, 0.0, 1e-10) << "x0 = " << x0;  // stuck on the floor
      worst_switch_time_error =
          std::max(worst_switch_time_error, std::fabs(s.first_step - std::atan(x0)));
    } else {
      EXPECT_NEAR(s.first_step, 0.5 * kHorizon, 1e-12) << "x0 = " << x0;  // equal steps
    }
    samples.push_back(s);
  }
  // Radau-IIA (order 3) with h0 = 0.1: measured 9.3e-7 and 4.9e-6.
  EXPECT_LT(worst_end_error, 1e-5);
  EXPECT_LT(worst_switch_time_error, 1e-5);
  double largest_jump = 0.0;
  for (size_t i = 1; i < samples.size(); ++i) {
    const Sample &a = samples[i - 1], &b = samples[i];
    const double dx0 = b.x0 - a.x0;
    // x(T) moves at most as much as x0 (plus the method's error), across x0* too.
    EXPECT_LE(std::fabs(b.end - a.end), dx0 + 2.0 * worst_end_error) << "x0 = " << b.x0;
    if (a.has_switch == b.has_switch) {
      // h_0 = t_c(x0) has slope 1 / (1 + x0^2) <= 1; T / 2 is constant.
      EXPECT_LE(std::fabs(b.first_step - a.first_step), dx0 + 2.0 * worst_switch_time_error);
    } else {
      largest_jump = std::max(largest_jump, std::fabs(b.first_step - a.first_step));
    }
  }
  // Between x0* - 1e-5 and x0* + 1e-5 the grid jumps from h_0 ~ T to T / 2.
  EXPECT_NEAR(largest_jump, 0.5 * kHorizon, 1e-4);
  hard_cases::recordNumber("end_state_error", worst_end_error);
  hard_cases::recordNumber("switch_time_error", worst_switch_time_error);
  hard_cases::recordNumber("grid_jump", largest_jump);
}

}  // namespace
