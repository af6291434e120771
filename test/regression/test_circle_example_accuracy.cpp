// Pozharskiy et al. 2024, Example 1 with the FESD integrator: accuracy, exact switch detection,
// convergence orders of FESD and the standard method, and step equilibration.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/circle_example.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"

namespace {

namespace example = fesd::circle_example;

/// `refine_elements` false: every step on `elements_per_step` elements, the paper's grid.
fesd::SimulationResult simulate(int stages, int total_elements, bool fesd_on = true,
                                int elements_per_step = 2,
                                std::shared_ptr<const fesd::DcsModel> model = example::model(),
                                bool refine_elements = true) {
  fesd::SimulationOptions options;
  options.discretization.num_stages = stages;
  options.discretization.num_elements = elements_per_step;
  options.discretization.switch_detection = fesd_on;
  options.refine_elements = refine_elements;
  fesd::FesdIntegrator integrator(std::move(model), options);
  return integrator.simulate(example::initialState(), example::horizon(),
                             total_elements / elements_per_step);
}

double terminalError(const fesd::SimulationResult& result) {
  return (result.trajectory.finalState() - example::exactState(example::horizon())).norm();
}

TEST(CircleExample, FesdIsAccurateAndDetectsBothSwitchesExactly) {
  const fesd::SimulationResult result = simulate(4, 20);
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  EXPECT_LT(terminalError(result), 1e-8);
  EXPECT_LE(result.totals.complementarity_residual, 1e-9);
  ASSERT_EQ(result.trajectory.switches.size(), 2u);
  const fesd::SwitchEvent& contact = result.trajectory.switches[0];
  const fesd::SwitchEvent& release = result.trajectory.switches[1];
  EXPECT_EQ(contact.kind, fesd::SwitchEvent::Kind::kContact);
  EXPECT_EQ(release.kind, fesd::SwitchEvent::Kind::kRelease);
  EXPECT_EQ(contact.constraint, 0);
  EXPECT_NEAR(contact.time, example::contactTime(), 1e-6);
  EXPECT_NEAR(release.time, example::releaseTime(), 1e-6);
  // lambda jumps to x1 = sqrt(3) at contact (Prop. 2) and vanishes continuously at release.
  const auto& after_contact = result.trajectory.elements[contact.element];
  EXPECT_NEAR(after_contact.stage_multipliers(0, 0), std::sqrt(3.0), 0.5);
  const auto& before_release = result.trajectory.elements[release.element - 1];
  EXPECT_NEAR(before_release.stage_multipliers(0, before_release.stage_multipliers.cols() - 1), 0.0,
              1e-6);
}

TEST(CircleExample, StandardMethodMissesTheSwitchTimes) {
  const fesd::SimulationResult result = simulate(2, 20, false);
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  EXPECT_GT(terminalError(result), 1e-3);
}

TEST(CircleExample, AutoDiffModelGivesTheSameSolution) {
  const auto autodiff = example::autodiffModel();
  const fesd::SimulationResult analytic = simulate(3, 20);
  const fesd::SimulationResult ad = simulate(3, 20, true, 2, autodiff);
  ASSERT_EQ(ad.status, fesd::SolveStatus::kSuccess) << ad.message;
  EXPECT_LT((analytic.trajectory.finalState() - ad.trajectory.finalState()).norm(), 1e-9);
}

/// Least-squares slope of log(error) against log(h) over the runs above the error floor.
double observedOrder(int stages, const std::vector<int>& totals, bool fesd_on) {
  std::vector<double> log_h, log_error;
  for (int total : totals) {
    const fesd::SimulationResult result = simulate(stages, total, fesd_on);
    EXPECT_EQ(result.status, fesd::SolveStatus::kSuccess)
        << "n_s=" << stages << " N=" << total << ": " << result.message;
    const double error = terminalError(result);
    if (error < 1e-9) continue;  // the homotopy's complementarity tolerance limits accuracy
    log_h.push_back(std::log(example::horizon() / total));
    log_error.push_back(std::log(error));
  }
  EXPECT_GE(log_h.size(), 3u) << "too few points above the error floor";
  const Eigen::Map<Eigen::VectorXd> x(log_h.data(), log_h.size());
  const Eigen::Map<Eigen::VectorXd> y(log_error.data(), log_error.size());
  const Eigen::VectorXd xc = x.array() - x.mean();
  return xc.dot(y.array().matrix() - Eigen::VectorXd::Constant(y.size(), y.mean())) /
         xc.squaredNorm();
}

TEST(CircleExample, FesdRecoversTheRadauOrder) {
  // Order 2 n_s - 1 (Pozharskiy et al. 2024, Sec. IV-A); the test allows 0.3 below it.
  EXPECT_GE(observedOrder(1, {20, 40, 80, 140}, true), 2 * 1 - 1.3);
  EXPECT_GE(observedOrder(2, {10, 20, 40, 80}, true), 2 * 2 - 1.3);
  EXPECT_GE(observedOrder(3, {10, 20, 40}, true), 2 * 3 - 1.3);
}

TEST(CircleExample, StandardMethodStaysAtLowOrder) {
  EXPECT_LE(observedOrder(2, {10, 20, 40, 80}, false), 2.3);
  EXPECT_LE(observedOrder(3, {10, 20, 40, 80}, false), 2.3);
}

TEST(CircleExample, StepEquilibrationKeepsStepsEqualAwayFromSwitches) {
  const int per_step = 4;
  const fesd::SimulationResult result = simulate(2, 20, true, per_step, example::model(), false);
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  const double h0 = example::horizon() / 20;
  int steps_with_switch = 0, steps_without = 0;
  for (int step = 0; step < 5; ++step) {
    bool has_switch = false;
    for (const fesd::SwitchEvent& event : result.trajectory.switches) {
      has_switch |= event.element > step * per_step && event.element < (step + 1) * per_step;
    }
    double shortest = 1e9, longest = 0.0;
    for (int e = step * per_step; e < (step + 1) * per_step; ++e) {
      shortest = std::min(shortest, result.trajectory.elements[e].step);
      longest = std::max(longest, result.trajectory.elements[e].step);
    }
    if (has_switch) {
      ++steps_with_switch;
      EXPECT_GT(longest - shortest, 1e-3 * h0) << "step " << step;
    } else {
      ++steps_without;
      EXPECT_LT(longest - shortest, 1e-8) << "step " << step;
    }
  }
  EXPECT_EQ(steps_with_switch, 2);
  EXPECT_EQ(steps_without, 3);
}

}  // namespace
