// Sensitivities of simulations over random push scenes and against time-stepping (slow: ~10 s):
// where defined they match central finite differences of runs with the same elements and
// switches; standard time-stepping's do not converge across a crossing.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/examples/filippov_examples.h"
#include "fesd_trajopt/examples/push_scenes.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"

namespace {

namespace ps = fesd::push_scenes;

fesd::SimulationResult simulate(const ps::PushScene& scene, bool sensitivities) {
  fesd::SimulationOptions options;
  options.sensitivities = sensitivities;
  return ps::simulate(scene, 25, options);
}

/// The same discrete map: elements, and each switch of the same pair and kind at the same
/// element boundary.
bool sameStructure(const fesd::SimulationResult& a, const fesd::SimulationResult& b) {
  if (a.status != fesd::SolveStatus::kSuccess || b.status != fesd::SolveStatus::kSuccess ||
      a.trajectory.elements.size() != b.trajectory.elements.size() ||
      a.trajectory.switches.size() != b.trajectory.switches.size()) {
    return false;
  }
  for (size_t i = 0; i < a.trajectory.switches.size(); ++i) {
    const fesd::SwitchEvent &s = a.trajectory.switches[i], &t = b.trajectory.switches[i];
    if (s.kind != t.kind || s.constraint != t.constraint || s.element != t.element) return false;
  }
  return true;
}

TEST(Sensitivities, RandomPushScenesMatchFiniteDifferencesWhereTheyAreDefined) {
  int defined = 0, compared = 0;
  for (unsigned seed = 0; seed < 12; ++seed) {
    SCOPED_TRACE(ps::randomPushScene(seed).describe());
    const ps::PushScene scene = ps::randomPushScene(seed);
    const fesd::SimulationResult result = simulate(scene, true);
    ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
    // Asking for them changes nothing in the simulation.
    const fesd::SimulationResult plain = simulate(scene, false);
    EXPECT_EQ(plain.trajectory.finalState(), result.trajectory.finalState());
    if (result.sensitivities.defined_steps < 25) {
      EXPECT_FALSE(result.sensitivities.why_undefined.empty());
      continue;
    }
    ++defined;
    const int dimension = scene.scene.dimension();
    const double h = 1e-5;
    for (int d = 0; d < scene.initialState().size(); ++d) {
      ps::PushScene plus = scene, minus = scene;
      plus.scene.bodies()[d / dimension].position(d % dimension) += h;
      minus.scene.bodies()[d / dimension].position(d % dimension) -= h;
      const fesd::SimulationResult up = simulate(plus, false), down = simulate(minus, false);
      if (!sameStructure(up, result) || !sameStructure(down, result)) continue;
      ++compared;
      const Eigen::VectorXd difference =
          (up.trajectory.finalState() - down.trajectory.finalState()) / (2.0 * h);
      EXPECT_LT((difference - result.sensitivities.states.back().col(d)).cwiseAbs().maxCoeff(),
                1e-6)
          << "start component " << d;
    }
  }
  // Measured: 10 of the 12 defined (two have a force vanishing without a release), 69 columns.
  EXPECT_GE(defined, 9);
  EXPECT_GE(compared, 40);
}

TEST(Sensitivities, TimeSteppingsDoNotConvergeAcrossACrossingWhileFesdsAreExact) {
  // x' = 2 - sign(x) from x0 = -0.77: dx(T)/dx0 = 1/3 (Nurkanovic et al. 2024, Sec. 4.6).
  for (const int steps : {16, 64, 256}) {
    for (const bool fesd : {true, false}) {
      fesd::SimulationOptions options;
      options.sensitivities = true;
      options.discretization.switch_detection = fesd;
      const fesd::SimulationResult result =
          fesd::FesdIntegrator(fesd::sign_example::model(), options)
              .simulate(Eigen::VectorXd::Constant(1, -0.77), 2.0, steps);
      ASSERT_EQ(result.status, fesd::SolveStatus::kSuccess) << result.message;
      ASSERT_EQ(result.sensitivities.defined_steps, steps) << result.sensitivities.why_undefined;
      const double error = std::fabs(result.sensitivities.states.back()(0, 0) - 1.0 / 3.0);
      if (fesd) {
        EXPECT_LT(error, 1e-12) << steps << " steps";
      } else {
        EXPECT_GT(error, 0.3) << steps << " steps";  // measured 0.33 to 1.13 on 4 to 256
      }
    }
  }
}

}  // namespace
