// Simulation steps as smooth square systems (integrator/active_set_step.cpp): the modes a step
// is predicted to keep, and a switch located from the signs the prediction violates, giving the
// solution the polished homotopy gives.
#include <cmath>

#include <gtest/gtest.h>

#include "fesd_trajopt/discretization/collocation_discretization.h"
#include "fesd_trajopt/discretization/pds_discretization.h"
#include "fesd_trajopt/examples/circle_example.h"
#include "fesd_trajopt/integrator/active_set_step.h"
#include "fesd_trajopt/integrator/fesd_integrator.h"
#include "fesd_trajopt/scene/scene.h"

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

TEST(ActiveSetStep, AContactMetAtTheStartWithinTheDataToleranceIsKept) {
  // Sliding along the line from a start 9e-10 inside it (as the step before can end): c(x0) is
  // data that counts as zero, and its product with the force (lambda = x1 > 1) no unknown can
  // lower; the slide is the answer, not a failure left to the homotopy.
  fesd::OcpDefinition ocp;
  ocp.model = example::model();
  ocp.initial_state = example::exactState(example::contactTime() + 0.3);
  ocp.initial_state(1) -= 9e-10;
  ocp.horizon = 0.46;
  ocp.num_intervals = 1;
  fesd::DiscretizationOptions options;
  options.num_stages = 3;
  options.num_elements = 2;
  const auto discretization = fesd::discretize(ocp, options);
  const fesd::PairModes sliding(2, std::vector<bool>{true});
  const fesd::ActiveSetStep fast = fesd::solveByActiveSets(
      *discretization, discretization->constantGuess(), sliding, fesd::ActiveSetOptions{});
  ASSERT_EQ(fast.outcome, fesd::ActiveSetOutcome::kPredicted) << fast.failure;
  EXPECT_GT(fast.report.complementarity_residual, 1e-9);  // with the start's data
  const fesd::Trajectory piece = discretization->extract(fast.report.solution.data());
  EXPECT_NEAR(piece.finalState()(1), -1.0, 1e-12);
  EXPECT_NEAR(piece.finalState()(0), example::exactState(example::contactTime() + 0.76)(0), 1e-6);
}

TEST(ActiveSetStep, StepsAreTiedWhereNoPairSwitchesInsideAControlInterval) {
  fesd::OcpDefinition ocp;
  ocp.model = example::model();
  ocp.initial_state = example::initialState();
  ocp.horizon = 1.0;
  ocp.num_intervals = 2;
  fesd::DiscretizationOptions options;
  options.num_elements = 3;
  const auto discretization = fesd::discretize(ocp, options);
  const auto& grid = dynamic_cast<const fesd::CollocationDiscretization&>(*discretization);
  // Six elements, a contact from element 2 on: boundaries 1, 4 and 5 keep their modes;
  // boundary 3 separates the control intervals.
  const fesd::PairModes modes{{false}, {false}, {true}, {true}, {true}, {true}};
  const std::vector<fesd::VariableTie> ties = fesd::equalStepTies(*discretization, modes);
  ASSERT_EQ(ties.size(), 3u);
  const int tied[][2] = {{0, 1}, {3, 4}, {4, 5}};
  for (size_t t = 0; t < ties.size(); ++t) {
    EXPECT_EQ(ties[t].first, grid.stepIndex(tied[t][0]));
    EXPECT_EQ(ties[t].second, grid.stepIndex(tied[t][1]));
  }
}

/// Two pushers (R = 1) at (-3, 0) and (3, 0) driven towards a passive disc (R = 1) at the origin
/// at unit speed: both touch it at t = 1 exactly, by symmetry.
struct SymmetricPush {
  fesd::Scene scene{2};
  Eigen::VectorXd control{Eigen::Vector4d(1.0, 0.0, -1.0, 0.0)};
  SymmetricPush() {
    scene.bodies().push_back({"left", 1.0, Eigen::Vector2d(-3.0, 0.0), true});
    scene.bodies().push_back({"right", 1.0, Eigen::Vector2d(3.0, 0.0), true});
    scene.bodies().push_back({"object", 1.0, Eigen::Vector2d(0.0, 0.0), false});
  }
  /// One step of `length` on 6 elements of 3 stages from x0 under `u`.
  std::unique_ptr<fesd::Discretization> step(const Eigen::VectorXd& x0, double length,
                                             const Eigen::VectorXd& u) const {
    fesd::OcpDefinition ocp;
    ocp.model = scene.model(scene.allPairs());
    ocp.initial_state = x0;
    ocp.horizon = length;
    fesd::DiscretizationOptions options;
    options.num_stages = 3;
    options.num_elements = 6;
    auto discretization = fesd::discretize(ocp, options);
    discretization->fixControl(0, u);
    return discretization;
  }
};

TEST(ActiveSetStep, TwoContactsAtOneBoundaryAreLocatedThoughTheyAddAnEquationTooMany) {
  SymmetricPush push;
  // Contact at t = 1 of a step of 1.3: boundary 5 (at 1.083 nominally) moves there.
  const auto discretization = push.step(push.scene.initialState(), 1.3, push.control);
  const std::vector<double> guess = discretization->constantGuess({push.control});
  const fesd::PairModes free(6, std::vector<bool>(3, false));
  const fesd::ActiveSetStep fast =
      fesd::solveByActiveSets(*discretization, guess, free, fesd::ActiveSetOptions{});
  ASSERT_EQ(fast.outcome, fesd::ActiveSetOutcome::kLocated) << fast.failure;
  ASSERT_EQ(fast.piece.switches.size(), 2u);
  for (const fesd::SwitchEvent& contact : fast.piece.switches) {
    EXPECT_NEAR(contact.time, 1.0, 1e-12);
  }
  // The pushers stop at the object, which stays where it is.
  EXPECT_NEAR(fast.piece.finalState()(0), -2.0, 1e-12);
  EXPECT_NEAR(fast.piece.finalState()(2), 2.0, 1e-12);
  EXPECT_NEAR(fast.piece.finalState().tail<2>().norm(), 0.0, 1e-12);
}

// A disc (R = 0.5) driven at u = (1, -0.2) slides along the floor y >= 0.5 (its force 0.2) into a
// ramp of slope 1/2 that starts at x = 0: the contact at t = 1 makes the floor's force jump to
// zero (the projection of u on the ramp, (0.72, 0.36), leaves the floor), a release that
// cross-complementarity alone forbids at that boundary (one equation too many).
TEST(ActiveSetStep, AContactThatEndsAnotherAtOnceLetsItsForceJump) {
  fesd::Scene scene(2);
  scene.bodies().push_back({"disc", 0.5, Eigen::Vector2d(-1.0, 0.5), true});
  const Eigen::Vector2d ramp_normal = Eigen::Vector2d(-1.0, 2.0).normalized();
  scene.walls().push_back({"floor", Eigen::Vector2d(0.0, 1.0), 0.0});
  scene.walls().push_back({"ramp", ramp_normal, ramp_normal.y() * 0.5 - 0.5});
  fesd::OcpDefinition ocp;
  ocp.model = scene.model(scene.allPairs());
  ocp.initial_state = scene.initialState();
  ocp.horizon = 1.3;
  fesd::DiscretizationOptions options;
  options.num_stages = 3;
  options.num_elements = 6;
  const auto discretization = fesd::discretize(ocp, options);
  const Eigen::Vector2d u(1.0, -0.2);
  discretization->fixControl(0, u);
  const std::vector<double> guess = discretization->constantGuess({u});
  ASSERT_EQ(scene.pairName(scene.allPairs()[0]), "disc/floor");
  const fesd::PairModes on_the_floor(6, std::vector<bool>{true, false});
  const fesd::ActiveSetStep fast =
      fesd::solveByActiveSets(*discretization, guess, on_the_floor, fesd::ActiveSetOptions{});
  ASSERT_EQ(fast.outcome, fesd::ActiveSetOutcome::kLocated) << fast.failure;
  ASSERT_EQ(fast.piece.switches.size(), 2u);
  for (const fesd::SwitchEvent& event : fast.piece.switches) {
    EXPECT_NEAR(event.time, 1.0, 1e-12);
  }
  // Along the floor at (1, 0) until t = 1, then up the ramp at (0.72, 0.36).
  EXPECT_LT((fast.piece.finalState() - Eigen::Vector2d(0.72 * 0.3, 0.5 + 0.36 * 0.3)).norm(),
            1e-12);
  EXPECT_LE(fast.report.complementarity_residual, 1e-9);
}

TEST(ActiveSetStep, AReleaseAtTheStartOfANewControlKeepsTheOtherStepsEqual) {
  SymmetricPush push;
  // The left pusher touching the object with a force carried over from a push; the new
  // control pulls it back at once. The force before the step's start counts in the step
  // equilibration's sums of boundary 1, which leaves that boundary's steps free.
  Eigen::VectorXd x0 = push.scene.initialState();
  x0.head<2>() << -2.0, 0.0;
  const Eigen::Vector4d pull(-1.0, 0.0, 0.0, 0.0);
  const auto discretization = push.step(x0, 0.6, pull);
  fesd::Trajectory previous;
  fesd::ElementValues last{0,
                           -0.1,
                           0.1,
                           Eigen::MatrixXd::Zero(6, 3),
                           Eigen::MatrixXd::Zero(3, 3),
                           Eigen::MatrixXd::Zero(3, 3),
                           Eigen::VectorXd()};
  last.stage_multipliers(1, 2) = 0.25;  // pair left/object (allPairs: left/right first)
  last.stage_constraints.row(0).setConstant(2.0);
  previous.elements.push_back(last);
  discretization->continueFrom(previous, false);
  const fesd::PairModes predicted = fesd::predictModes(&previous, {}, 6, 1e-9);
  ASSERT_TRUE(predicted[0][1]);
  const fesd::ActiveSetStep fast = fesd::solveByActiveSets(
      *discretization, discretization->constantGuess({pull}), predicted, fesd::ActiveSetOptions{});
  ASSERT_EQ(fast.outcome, fesd::ActiveSetOutcome::kLocated) << fast.failure;
  EXPECT_EQ(fast.mode_sequences, 2);
  for (const fesd::ElementValues& element : fast.piece.elements) {
    EXPECT_NEAR(element.step, 0.1, 1e-15);
  }
  EXPECT_NEAR(fast.piece.finalState()(0), -2.6, 1e-12);
}

}  // namespace
