// Simulation steps as smooth square systems (integrator/active_set_step.cpp): the modes a step
// is predicted to keep, and a switch located from the signs the prediction violates, giving the
// solution the polished homotopy gives.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/discretization/pds_discretization.h"
#include "fesd_trajopt/examples/circle_example.h"
#include "fesd_trajopt/integrator/active_set_step.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"

namespace {

namespace example = fesd::circle_example;

TEST(ActiveSetStep, ModesArePredictedFromThePreviousStepsEndOrTheStartState) {
  fesd::Trajectory previous;
  fesd::ElementValues last{0,
                           0.0,
                           0.1,
                           Eigen::MatrixXd::Zero(2, 2),
                           Eigen::MatrixXd::Zero(3, 2),
                           Eigen::MatrixXd::Zero(3, 2),
                           Eigen::VectorXd()};
  last.stage_multipliers.col(1) << 2.0, 0.0, 0.0;  // in contact, free, both zero (biactive)
  last.stage_constraints.col(1) << 0.0, 1.0, 0.0;
  previous.elements.push_back(last);
  const fesd::PairModes predicted = fesd::predictModes(&previous, {false, true, true}, 2, 1e-9);
  ASSERT_EQ(predicted.size(), 2u);
  for (const std::vector<bool>& element : predicted) {
    EXPECT_EQ(element, (std::vector<bool>{true, false, false}));
  }
  EXPECT_EQ(fesd::predictModes(nullptr, {false, true}, 3, 1e-9),
            fesd::PairModes(3, std::vector<bool>{false, true}));
}

/// One step of Example 1 of length 0.46 on 2 elements that reaches the circle 0.2 after its start.
struct ContactStep {
  std::unique_ptr<fesd::Discretization> discretization;
  ContactStep() {
    fesd::OcpDefinition step;
    step.model = example::model();
    step.initial_state = example::exactState(example::contactTime() - 0.2);
    step.horizon = 0.46;
    step.num_intervals = 1;
    fesd::DiscretizationOptions options;
    options.num_stages = 3;
    options.num_elements = 2;
    discretization = fesd::discretize(step, options);
  }
};

TEST(ActiveSetStep, AContactIsLocatedAtAnElementBoundaryAsThePolishedHomotopyPlacesIt) {
  ContactStep step;
  fesd::Discretization& discretization = *step.discretization;
  const std::vector<double> guess = discretization.constantGuess();
  const fesd::PairModes free(2, std::vector<bool>{false});
  const fesd::ActiveSetStep fast =
      fesd::solveByActiveSets(discretization, guess, free, fesd::ActiveSetOptions{});
  ASSERT_EQ(fast.outcome, fesd::ActiveSetOutcome::kLocated) << fast.failure;
  EXPECT_EQ(fast.mode_sequences, 2);
  EXPECT_EQ(fast.report.complementarity_residual, 0.0);
  const fesd::Trajectory piece = discretization.extract(fast.report.solution.data());
  ASSERT_EQ(piece.switches.size(), 1u);
  EXPECT_NEAR(piece.switches[0].time, 0.2, 1e-6);  // n_s = 3 on an element of 0.2
  EXPECT_DOUBLE_EQ(piece.times[1], piece.switches[0].time);

  fesd::MpccSolver homotopy(fesd::steepHomotopy());
  const fesd::MpccReport polished = homotopy.solve(discretization.nlp(), guess);
  ASSERT_TRUE(polished.converged() && polished.polished) << polished.message;
  double largest = 0.0;
  for (size_t v = 0; v < polished.solution.size(); ++v) {
    largest = std::max(largest, std::fabs(polished.solution[v] - fast.report.solution[v]));
  }
  EXPECT_LT(largest, 1e-9);
}

TEST(ActiveSetStep, ModesThatContradictTheStartAreRefusedForTheHomotopy) {
  ContactStep step;
  // Active from the start, but the start is 0.2 away from the circle: c(x0) > 0 is data.
  const fesd::PairModes touching(2, std::vector<bool>{true});
  const fesd::ActiveSetStep fast =
      fesd::solveByActiveSets(*step.discretization, step.discretization->constantGuess(), touching,
                              fesd::ActiveSetOptions{});
  EXPECT_EQ(fast.outcome, fesd::ActiveSetOutcome::kFailed);
  EXPECT_NE(fast.failure.find("contradict"), std::string::npos) << fast.failure;
}

}  // namespace
