// Sensitivities of simulations (integrator/step_sensitivity.cpp): the implicit function theorem on
// each step's FESD system, against analytic derivatives across a crossing and into a sliding mode,
// and the cases where they are not defined.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/filippov_examples.h"
#include "fesd_trajopt/examples/push_scenes.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/integrator/step_sensitivity.h"
#include "fesd_trajopt/model/stewart_model.h"
#include "fesd_trajopt/scene/scene.h"

namespace {

/// x1' = u - sign(x1), x2' = sign(x1): from x1(0) > 0 with |u| < 1, x1 reaches 0 at
/// t* = x1(0) / (1 - u) and slides there (Filippov: theta_0 - theta_1 = u), so x1(T) = 0 and
/// x2(T) = x2(0) + t* + u (T - t*) = x2(0) + x1(0) + u T.
struct SlidingModes {
  template <class T>
  void operator()(const T*, const T* u, T* F) const {
    F[0] = u[0] - T(1.0);  // x1 > 0
    F[1] = T(1.0);
    F[2] = u[0] + T(1.0);  // x1 < 0
    F[3] = T(-1.0);
  }
};
struct FirstState {
  template <class T>
  void operator()(const T* x, T* c) const {
    c[0] = x[0];
  }
};

std::shared_ptr<const fesd::StewartModel> slidingModel() {
  return fesd::makeSwitchingModel(2, 1, {1}, SlidingModes{}, FirstState{}, "sliding");
}

fesd::SimulationResult simulateWithSensitivities(
    std::shared_ptr<const fesd::DynamicsModel> model, const Eigen::VectorXd& x0, double horizon,
    int steps, const std::vector<Eigen::VectorXd>& controls = {}) {
  fesd::SimulationOptions options;
  options.sensitivities = true;
  return fesd::FesdIntegrator(std::move(model), options).simulate(x0, horizon, steps, controls);
}

TEST(StepSensitivity, ACrossingOfTwoMinusSignHasTheExactDerivativeOneThird) {
  // x' = 2 - sign(x) from x0 < 0: x(T) = T + x0 / 3 after the crossing at t* = -x0 / 3; the
  // smooth pieces alone would give dx(T)/dx0 = 1.
  for (const double x0 : {-1.0, -0.77, -0.3}) {
    const fesd::SimulationResult result = simulateWithSensitivities(
        fesd::sign_example::model(), Eigen::VectorXd::Constant(1, x0), 2.0, 10);
    ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
    const fesd::SimulationSensitivities& s = result.sensitivities;
    ASSERT_EQ(s.states.size(), 10u);
    EXPECT_EQ(s.defined_steps, 10) << s.why_undefined;
    EXPECT_NEAR(result.trajectory.finalState()(0), 2.0 + x0 / 3.0, 1e-9);
    EXPECT_NEAR(s.states.back()(0, 0), 1.0 / 3.0, 1e-8) << "x0 = " << x0;
    // Stewart's crossing: one mode leaves and the other enters, at t* = -x0 / 3.
    ASSERT_EQ(s.switch_times.size(), 2u);
    for (size_t i = 0; i < 2; ++i) {
      EXPECT_NEAR(result.trajectory.switches[i].time, -x0 / 3.0, 1e-9);
      EXPECT_NEAR(s.switch_times[i](0), -1.0 / 3.0, 1e-8);
    }
    // Before the crossing the flow is x0 + 3 t: derivative 1.
    const int before = static_cast<int>(std::floor(-x0 / 3.0 / 0.2));
    if (before > 0) {
      EXPECT_NEAR(s.states[before - 1](0, 0), 1.0, 1e-10);
    }
  }
}

TEST(StepSensitivity, ASlidingModeHasTheExactDerivativesByTheStartAndTheControl) {
  const double u = 0.5, horizon = 2.0;
  const Eigen::Vector2d x0(0.37, 0.2);
  const fesd::SimulationResult result =
      simulateWithSensitivities(slidingModel(), x0, horizon, 8, {Eigen::VectorXd::Constant(1, u)});
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  const fesd::SimulationSensitivities& s = result.sensitivities;
  ASSERT_EQ(s.defined_steps, 8) << s.why_undefined;
  const Eigen::MatrixXd& last = s.states.back();
  ASSERT_EQ(last.cols(), 2 + 8);
  EXPECT_NEAR(result.trajectory.finalState()(1), x0(1) + x0(0) + u * horizon, 1e-9);
  EXPECT_NEAR(last(0, 0), 0.0, 1e-8);
  EXPECT_NEAR(last(0, 1), 0.0, 1e-8);
  EXPECT_NEAR(last(1, 0), 1.0, 1e-8);
  EXPECT_NEAR(last(1, 1), 1.0, 1e-8);
  // The control held over all steps: the sum of the steps' blocks.
  EXPECT_NEAR(last.rightCols(8).row(1).sum(), horizon, 1e-8);
  EXPECT_NEAR(last.rightCols(8).row(0).sum(), 0.0, 1e-8);
  ASSERT_FALSE(s.switch_times.empty());
  EXPECT_NEAR(result.trajectory.switches[0].time, x0(0) / (1.0 - u), 1e-9);
  EXPECT_NEAR(s.switch_times[0](0), 1.0 / (1.0 - u), 1e-8);
  EXPECT_NEAR(s.switch_times[0].tail(8).sum(), x0(0) / ((1.0 - u) * (1.0 - u)), 1e-8);
}

/// A pusher (R = 0.5, actuated) at (-distance, offset) and a puck (R = 0.5) at the origin; the
/// pusher moves at (1, 0) for two seconds, then back at (-1, 0) for one, in steps of 0.5 s: a
/// contact, and a release when the pusher turns (a control jump, at a step's end).
struct PushAndRelease {
  fesd::Scene scene{2};
  std::vector<Eigen::VectorXd> controls;
  explicit PushAndRelease(double offset, double distance = 2.0) {
    scene.bodies().push_back({"pusher", 0.5, Eigen::Vector2d(-distance, offset), true});
    scene.bodies().push_back({"puck", 0.5, Eigen::Vector2d(0.0, 0.0), false});
    for (int k = 0; k < 6; ++k) controls.push_back(Eigen::Vector2d(k < 4 ? 1.0 : -1.0, 0.0));
  }
  fesd::SimulationResult simulate(const Eigen::VectorXd& x0,
                                  const std::vector<Eigen::VectorXd>& commands) const {
    return simulateWithSensitivities(scene.model(scene.allPairs()), x0, 3.0, 6, commands);
  }
};

TEST(StepSensitivity, AHeadOnPushAndReleaseHaveTheSaltationOfTheProjection) {
  // Head on, the projection halves the pusher's velocity between the two discs after the
  // contact at t* = q0 - p0 - 1 = 1.2, until the pusher turns at T1 = 2: the puck ends at
  // q0 + (T1 - t*) / 2, so dq/dp0 = dq/dq0 = 1/2 and dq/du = 1/2 per second of pushing,
  // where the smooth pieces alone give 0, 1 and 0.
  const PushAndRelease push(0.0, 2.2);
  const fesd::SimulationResult result = push.simulate(push.scene.initialState(), push.controls);
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  const fesd::SimulationSensitivities& s = result.sensitivities;
  ASSERT_EQ(s.defined_steps, 6) << s.why_undefined;
  const Eigen::MatrixXd& last = s.states.back();  // x = (pusher, puck), u per step (2 each)
  EXPECT_NEAR(result.trajectory.finalState()(2), 0.4, 1e-9);
  EXPECT_NEAR(last(2, 0), 0.5, 1e-8);
  EXPECT_NEAR(last(2, 2), 0.5, 1e-8);
  EXPECT_NEAR(last(2, 1), 0.0, 1e-8);
  EXPECT_NEAR(last(0, 0), 0.5, 1e-8);  // the pusher lost what the puck gained
  EXPECT_NEAR(last(0, 2), 0.5, 1e-8);
  // The puck moves half of what the pusher travels beyond the gap, however a step's command
  // changes the contact's time: 0.5 * 0.5 per unit of command in each pushing step, nothing
  // after the turn.
  for (int k = 0; k < 4; ++k) EXPECT_NEAR(last(2, 4 + 2 * k), 0.25, 1e-8) << "step " << k;
  for (int k = 4; k < 6; ++k) EXPECT_NEAR(last(2, 4 + 2 * k), 0.0, 1e-8) << "step " << k;
  ASSERT_EQ(s.switch_times.size(), 2u);  // the contact and the release at the turn
  EXPECT_NEAR(result.trajectory.switches[0].time, 1.2, 1e-9);
  EXPECT_NEAR(s.switch_times[0](0), -1.0, 1e-8);
  EXPECT_NEAR(s.switch_times[0](2), 1.0, 1e-8);
  // The contact comes earlier by the step's length per unit of command before it, by 0.2 in
  // step 2 where it happens; the release stays at the turn.
  EXPECT_NEAR(s.switch_times[0](4), -0.5, 1e-8);
  EXPECT_NEAR(s.switch_times[0](6), -0.5, 1e-8);
  EXPECT_NEAR(s.switch_times[0](8), -0.2, 1e-8);
  EXPECT_NEAR(s.switch_times[0](10), 0.0, 1e-8);
  EXPECT_NEAR(result.trajectory.switches[1].time, 2.0, 1e-9);
  EXPECT_LT(s.switch_times[1].cwiseAbs().maxCoeff(), 1e-8);
}

/// The state at the element boundary at time t.
Eigen::VectorXd stateAt(const fesd::Trajectory& trajectory, double t) {
  for (size_t i = 0; i < trajectory.times.size(); ++i) {
    if (std::fabs(trajectory.times[i] - t) < 1e-12) return trajectory.states[i];
  }
  ADD_FAILURE() << "no element boundary at t = " << t;
  return Eigen::VectorXd();
}

TEST(StepSensitivity, AnOffCentrePushMatchesCentralFiniteDifferences) {
  // Off centre the contact normal turns as the discs move: no closed form, but the perturbed
  // runs keep the same contact and release, so central differences (h = 1e-5) are valid.
  const PushAndRelease push(0.3);
  const Eigen::VectorXd x0 = push.scene.initialState();
  const fesd::SimulationResult result = push.simulate(x0, push.controls);
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  ASSERT_EQ(result.sensitivities.defined_steps, 6) << result.sensitivities.why_undefined;
  const double h = 1e-5;
  const int nx = static_cast<int>(x0.size());
  for (int column = 0; column < nx + 6 * 2; ++column) {
    SCOPED_TRACE("column " + std::to_string(column));
    Eigen::VectorXd x_plus = x0, x_minus = x0;
    std::vector<Eigen::VectorXd> u_plus = push.controls, u_minus = push.controls;
    if (column < nx) {
      x_plus(column) += h;
      x_minus(column) -= h;
    } else {
      u_plus[(column - nx) / 2]((column - nx) % 2) += h;
      u_minus[(column - nx) / 2]((column - nx) % 2) -= h;
    }
    const fesd::SimulationResult up = push.simulate(x_plus, u_plus);
    const fesd::SimulationResult down = push.simulate(x_minus, u_minus);
    ASSERT_EQ(up.trajectory.switches.size(), result.trajectory.switches.size());
    ASSERT_EQ(down.trajectory.switches.size(), result.trajectory.switches.size());
    for (int k = 0; k < 6; ++k) {
      const double step_end = 0.5 * (k + 1);
      const Eigen::VectorXd difference =
          (stateAt(up.trajectory, step_end) - stateAt(down.trajectory, step_end)) / (2 * h);
      EXPECT_LT((difference - result.sensitivities.states[k].col(column)).cwiseAbs().maxCoeff(),
                1e-6)
          << "step " << k;
    }
    for (size_t i = 0; i < result.trajectory.switches.size(); ++i) {
      const double difference =
          (up.trajectory.switches[i].time - down.trajectory.switches[i].time) / (2 * h);
      EXPECT_NEAR(difference, result.sensitivities.switch_times[i](column), 1e-6);
    }
  }
}

TEST(StepSensitivity, AGrazingContactIsNotDifferentiable) {
  // The pusher passes the puck at exactly the contact distance at t = 2.
  PushAndRelease graze(1.0);
  const fesd::SimulationResult result =
      simulateWithSensitivities(graze.scene.model(graze.scene.allPairs()),
                                graze.scene.initialState(), 3.5, 5, {Eigen::Vector2d(1.0, 0.0)});
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  const fesd::SimulationSensitivities& s = result.sensitivities;
  EXPECT_EQ(s.defined_steps, 2);
  EXPECT_NE(s.why_undefined.find("touches"), std::string::npos) << s.why_undefined;
  EXPECT_TRUE(s.states[1].allFinite());
  EXPECT_TRUE(s.states[2].array().isNaN().all());
}

TEST(StepSensitivity, AContactRightAtAStepsEndIsNotDifferentiable) {
  // From -2 the pusher touches the puck at t = 1, the end of step 1 (steps of 0.5 s): a start a
  // little farther back moves the contact into step 2, a little nearer into step 1.
  const PushAndRelease push(0.0, 2.0);
  const fesd::SimulationResult result = push.simulate(push.scene.initialState(), push.controls);
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  EXPECT_EQ(result.sensitivities.defined_steps, 1);
  EXPECT_NE(result.sensitivities.why_undefined.find("end of a step"), std::string::npos)
      << result.sensitivities.why_undefined;
}

TEST(StepSensitivity, AReleaseRightAtAStepsEndIsSmooth) {
  // A PDS lets go as its force falls to zero: the velocity does not jump, so a release at a step's
  // end (here the pusher of push scene 12 passing the puck at t = 5 T / 10) keeps the flow
  // differentiable, and the derivatives converge to a fine run's.
  fesd::push_scenes::PushScene scene = fesd::push_scenes::randomPushScene(12);
  scene.horizon = 2.0 * scene.releaseTime();
  fesd::SimulationOptions options;
  options.sensitivities = true;
  const fesd::SimulationResult coarse = fesd::push_scenes::simulate(scene, 10, options);
  const fesd::SimulationResult fine = fesd::push_scenes::simulate(scene, 160, options);
  ASSERT_EQ(coarse.sensitivities.defined_steps, 10) << coarse.sensitivities.why_undefined;
  ASSERT_EQ(fine.sensitivities.defined_steps, 160) << fine.sensitivities.why_undefined;
  EXPECT_LT((coarse.sensitivities.states.back().leftCols(4) -
             fine.sensitivities.states.back().leftCols(4))
                .cwiseAbs()
                .maxCoeff(),
            1e-4);  // measured 1.3e-5
}

TEST(StepSensitivity, TwoContactsAtOneInstantAreNotDifferentiable) {
  // Two pushers at (-3, 0) and (3, 0) meet a disc at the origin at t = 1 by symmetry; a shift of
  // either start lets one of them touch first.
  fesd::Scene scene{2};
  scene.bodies().push_back({"left", 1.0, Eigen::Vector2d(-3.0, 0.0), true});
  scene.bodies().push_back({"right", 1.0, Eigen::Vector2d(3.0, 0.0), true});
  scene.bodies().push_back({"object", 1.0, Eigen::Vector2d(0.0, 0.0), false});
  const fesd::SimulationResult result =
      simulateWithSensitivities(scene.model(scene.allPairs()), scene.initialState(), 2.0, 5,
                                {Eigen::Vector4d(1.0, 0.0, -1.0, 0.0)});
  ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
  EXPECT_EQ(result.sensitivities.defined_steps, 2);
  EXPECT_NE(result.sensitivities.why_undefined.find("switch together"), std::string::npos)
      << result.sensitivities.why_undefined;
}

TEST(StepSensitivity, AStepOutOfTimeLeavesItsDerivativesUndefined) {
  fesd::SimulationOptions options;
  options.sensitivities = true;
  options.wall_time_budget = 1e-9;
  const fesd::SimulationResult result = fesd::FesdIntegrator(fesd::sign_example::model(), options)
                                            .simulate(Eigen::VectorXd::Constant(1, -1.0), 2.0, 4);
  EXPECT_EQ(result.status, fesd::SolveStatus::kTimeout);
  EXPECT_EQ(result.sensitivities.defined_steps, 0);
  EXPECT_FALSE(result.sensitivities.why_undefined.empty());
}

TEST(StepSensitivity, TheSensitivityErrorConvergesAtTheIntegratorsOrder) {
  // Radau IIA with 2 stages has order 3: halving the step divides the error by about 8.
  const Eigen::Vector2d x0 = fesd::spiral_example::initialState();
  const double horizon = fesd::spiral_example::horizon();
  const Eigen::Matrix2d exact = fesd::spiral_example::exactSensitivity(x0, horizon);
  std::vector<double> errors;
  for (const int steps : {8, 16, 32}) {
    const fesd::SimulationResult result =
        simulateWithSensitivities(fesd::spiral_example::model(), x0, horizon, steps);
    ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
    ASSERT_EQ(result.sensitivities.defined_steps, steps) << result.sensitivities.why_undefined;
    errors.push_back((result.sensitivities.states.back() - exact).norm() / exact.norm());
  }
  for (size_t i = 1; i < errors.size(); ++i) {
    const double order = std::log2(errors[i - 1] / errors[i]);
    EXPECT_GT(order, 2.6) << errors[i - 1] << " -> " << errors[i];
  }
  EXPECT_LT(errors.back(), 1e-2);
}

}  // namespace
