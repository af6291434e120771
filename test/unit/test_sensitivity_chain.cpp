// The chain rule over a simulation's parts (integrator/sensitivity_chain.cpp): derivatives by the
// start state and the controls of each step, element boundary times, and undefined parts.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/integrator/sensitivity_chain.h"

namespace {

/// A part of a scalar system x' = a x + b u over one step: x_end = e^a x + (e^a - 1) / a * b u,
/// with `elements` elements whose lengths depend on (x, u) as given.
fesd::StepSensitivity linearPart(double a, double b, const Eigen::MatrixXd& steps) {
  fesd::StepSensitivity part;
  part.defined = true;
  part.final_state.resize(1, 2);
  part.final_state << std::exp(a), (std::exp(a) - 1.0) / a * b;
  part.steps = steps;
  return part;
}

TEST(SensitivityChain, PartsAndStepsChainByTheProductRule) {
  fesd::SensitivityChain chain(1, 1, 2);
  // Step 0 in two parts, step 1 in one.
  Eigen::MatrixXd steps(2, 2);
  steps << 0.1, 0.2, -0.1, -0.2;  // a switch between the two elements moves with (x, u)
  const fesd::StepSensitivity first = linearPart(0.5, 1.0, steps);
  const fesd::StepSensitivity second = linearPart(-0.3, 2.0, Eigen::MatrixXd::Zero(1, 2));
  chain.addPart(first, 0, 2);
  chain.addPart(second, 0, 1);
  chain.endStep();
  chain.addPart(first, 1, 2);
  chain.endStep();
  fesd::SwitchEvent at_first_boundary{0.0, 0, fesd::SwitchEvent::Kind::kContact, 1};
  fesd::SwitchEvent in_step_one{0.0, 0, fesd::SwitchEvent::Kind::kContact, 4};
  const fesd::SimulationSensitivities result = chain.finish({at_first_boundary, in_step_one});
  ASSERT_EQ(result.defined_steps, 2);
  ASSERT_EQ(result.states.size(), 2u);
  const double a1 = first.final_state(0, 0), b1 = first.final_state(0, 1);
  const double a2 = second.final_state(0, 0), b2 = second.final_state(0, 1);
  // After step 0: x = a2 (a1 x0 + b1 u0) + b2 u0.
  EXPECT_NEAR(result.states[0](0, 0), a2 * a1, 1e-15);
  EXPECT_NEAR(result.states[0](0, 1), a2 * b1 + b2, 1e-15);
  EXPECT_EQ(result.states[0](0, 2), 0.0);  // u1 acts after step 0
  // After step 1: x = a1 x_1 + b1 u1.
  EXPECT_NEAR(result.states[1](0, 0), a1 * a2 * a1, 1e-15);
  EXPECT_NEAR(result.states[1](0, 1), a1 * (a2 * b1 + b2), 1e-15);
  EXPECT_NEAR(result.states[1](0, 2), b1, 1e-15);
  // The boundary after the first element of the first part: dh_0; in step 1 the same by the
  // step's start state (chained) and its own control.
  ASSERT_EQ(result.switch_times.size(), 2u);
  EXPECT_NEAR(result.switch_times[0](0), 0.1, 1e-15);
  EXPECT_NEAR(result.switch_times[0](1), 0.2, 1e-15);
  EXPECT_NEAR(result.switch_times[1](0), 0.1 * result.states[0](0, 0), 1e-15);
  EXPECT_NEAR(result.switch_times[1](1), 0.1 * result.states[0](0, 1), 1e-15);
  EXPECT_NEAR(result.switch_times[1](2), 0.2, 1e-15);
}

TEST(SensitivityChain, AnUndefinedPartLeavesEveryLaterStepUndefined) {
  fesd::SensitivityChain chain(1, 1, 3);
  chain.addPart(linearPart(0.5, 1.0, Eigen::MatrixXd::Zero(1, 2)), 0, 1);
  chain.endStep();
  fesd::StepSensitivity grazing;
  grazing.why_undefined = "pair 0 touches";
  chain.addPart(grazing, 1, 1);
  chain.endStep();
  chain.addPart(linearPart(0.5, 1.0, Eigen::MatrixXd::Zero(1, 2)), 2, 1);
  chain.endStep();
  fesd::SwitchEvent late{0.0, 0, fesd::SwitchEvent::Kind::kRelease, 3};
  const fesd::SimulationSensitivities result = chain.finish({late});
  EXPECT_EQ(result.defined_steps, 1);
  EXPECT_EQ(result.why_undefined, "step 1: pair 0 touches");
  EXPECT_TRUE(result.states[0].allFinite());
  EXPECT_TRUE(result.states[1].array().isNaN().all());
  EXPECT_TRUE(result.states[2].array().isNaN().all());
  EXPECT_TRUE(result.switch_times[0].array().isNaN().all());
}

}  // namespace
