#include "fesd_trajopt/discretization/stewart_discretization.h"

#include <algorithm>
#include <stdexcept>

namespace fesd {
namespace {

constexpr double kInf = NlpAssembly::kInfinity;

}  // namespace

StewartDiscretization::StewartDiscretization(OcpDefinition ocp, DiscretizationOptions options)
    : CollocationDiscretization(std::move(ocp), options),
      model_(std::dynamic_pointer_cast<const StewartModel>(ocp_.model)) {
  if (!model_) throw std::invalid_argument("StewartDiscretization: the model is no StewartModel");
  if (!options_.gap_guards.empty()) {
    throw std::invalid_argument("StewartDiscretization: gap guards are for a PDS's constraints");
  }
  if (ocp_.force_constraints) {
    throw std::invalid_argument("StewartDiscretization: force constraints are for a PDS's forces");
  }
  nf_ = model_->numModes();
  nsys_ = model_->numSubsystems();
  steps_free_ = options_.switch_detection;
  stage_at_end_ = tableau_.lastStageIsEndPoint();
  buildVariables();
  buildDynamics();
  buildBoundaryPoints();
  buildComplementarity();
  buildStepEquilibration();
  addCostsAndConstraints(nlp_, grid_, ocp_, tableau_);
  nlp_.finalize();
  nlp_.setEvaluationThreads(options_.evaluation_threads);
}

void StewartDiscretization::buildVariables() {
  addStartState();
  if (ocp_.initial_state_lower.size()) {
    releaseInitialState();
    for (int d = 0; d < nx_; ++d) nlp_.initialGuess()[start_state_ + d] = ocp_.initial_state(d);
  } else {
    setInitialState(ocp_.initial_state);
  }
  buildGrid([&](int) {
    Element element;
    element.start_state = elements_.empty() ? start_state_ : elements_.back().end_state;
    ElementStates states;
    for (int j = 0; j < tableau_.stages; ++j) {
      StagePoint point;
      point.x = addStateVariables();
      point.theta = nlp_.addVariables(nf_, 0.0, kInf);
      point.lambda = nlp_.addVariables(nf_, 0.0, kInf);
      point.mu = nlp_.addVariables(nsys_, -kInf, kInf);
      element.stages.push_back(point);
      states.stages.push_back(point.x);
    }
    element.end_state = stage_at_end_ ? element.stages.back().x : addStateVariables();
    states.end = element.end_state;
    elements_.push_back(element);
    return states;
  });
}

void StewartDiscretization::buildAlgebraicRows(int state, int theta, int lambda, int mu,
                                               bool with_theta) {
  // lambda_i + mu_k(i) - g_i(x) = 0
  const int row = nlp_.addRows(nf_, 0.0, 0.0);
  for (int i = 0; i < nf_; ++i) {
    nlp_.addLinear(row + i, lambda + i, 1.0);
    nlp_.addLinear(row + i, mu + model_->subsystemOf(i), 1.0);
  }
  std::vector<int> inputs;
  for (int d = 0; d < nx_; ++d) inputs.push_back(state + d);
  nlp_.addFunctionTerm(model_->indicators(), inputs, -1, {{row, -1.0}});
  if (!with_theta) return;
  // e^T theta^k = 1
  const int sum_row = nlp_.addRows(nsys_, 1.0, 1.0);
  for (int i = 0; i < nf_; ++i) nlp_.addLinear(sum_row + model_->subsystemOf(i), theta + i, 1.0);
}

void StewartDiscretization::buildDynamics() {
  for (int e = 0; e < numElements(); ++e) {
    const Element& element = elements_[e];
    std::vector<int> modes;
    for (const StagePoint& point : element.stages) modes.push_back(point.theta);
    addRungeKuttaRows(e, model_->velocity(), modes, nf_);
    for (const StagePoint& point : element.stages) {
      buildAlgebraicRows(point.x, point.theta, point.lambda, point.mu, true);
    }
  }
  if (steps_free_) addIntervalLengthRows(nlp_, grid_, ocp_);
}

void StewartDiscretization::buildBoundaryPoints() {
  if (!steps_free_) return;
  for (int e = 0; e < numElements(); ++e) {
    Element& element = elements_[e];
    if (e > 0 && stage_at_end_) {
      // eq. 27: lambda and mu at the boundary are the previous element's last stage values.
      element.start = {elements_[e - 1].stages.back().lambda, elements_[e - 1].stages.back().mu};
      continue;
    }
    element.start = addBoundaryPoint(element.start_state);
  }
  // With c_ns != 1 the last element's end needs its own point too: without it a switch right
  // at the end of an integrator step or control interval would go undetected.
  if (!stage_at_end_) final_boundary_ = addBoundaryPoint(elements_.back().end_state);
}

StewartDiscretization::BoundaryPoint StewartDiscretization::addBoundaryPoint(int state) {
  BoundaryPoint point;
  point.lambda = nlp_.addVariables(nf_, 0.0, kInf);
  point.mu = nlp_.addVariables(nsys_, -kInf, kInf);
  buildAlgebraicRows(state, -1, point.lambda, point.mu, false);
  return point;
}

std::vector<int> StewartDiscretization::closureLambdas(int element) const {
  const Element& e = elements_[element];
  std::vector<int> lambdas{e.start.lambda};
  for (const StagePoint& point : e.stages) {
    if (point.lambda != e.start.lambda) lambdas.push_back(point.lambda);
  }
  if (!stage_at_end_) {
    lambdas.push_back(element + 1 < numElements() ? elements_[element + 1].start.lambda
                                                  : final_boundary_.lambda);
  }
  return lambdas;
}

void StewartDiscretization::buildComplementarity() {
  for (int e = 0; e < numElements(); ++e) {
    const Element& element = elements_[e];
    for (int i = 0; i < nf_; ++i) {
      if (!steps_free_) {
        for (const StagePoint& point : element.stages) {
          addPairComplementarity(e, i, {{point.theta + i, 1.0}}, {{point.lambda + i, 1.0}}, false);
        }
        continue;
      }
      // Cross-complementarity (eq. 28): every stage theta_i of the element against every
      // lambda_i of its closure, as one product of sums or pair by pair.
      LinearExpression theta_side, lambda_side;
      for (const StagePoint& point : element.stages) theta_side.push_back({point.theta + i, 1.0});
      for (int lambda : closureLambdas(e)) lambda_side.push_back({lambda + i, 1.0});
      if (options_.cross_complementarity == CrossComplementarity::kElementSums) {
        addPairComplementarity(e, i, theta_side, lambda_side, false);
        continue;
      }
      for (const LinearTerm& theta : theta_side) {
        for (const LinearTerm& lambda : lambda_side) {
          addPairComplementarity(e, i, {theta}, {lambda}, false);
        }
      }
    }
  }
}

void StewartDiscretization::buildStepEquilibration() {
  if (!steps_free_ || options_.filippov.step_equilibration == StepEquilibration::kNone) return;
  for (int element : innerBoundaries()) {
    Equilibration eq;
    eq.element = element;
    eq.inputs = {grid_.steps[element - 1], grid_.steps[element]};
    std::vector<int> blocks;  // first variable of each n_f block, in input order
    auto positions = [&](const std::vector<int>& block_starts) {
      std::vector<int> result;
      for (int start : block_starts) {
        auto found = std::find(blocks.begin(), blocks.end(), start);
        result.push_back(static_cast<int>(found - blocks.begin()));
        if (found == blocks.end()) blocks.push_back(start);
      }
      return result;
    };
    auto stage_thetas = [&](int e) {
      std::vector<int> thetas;
      for (const StagePoint& point : elements_[e].stages) thetas.push_back(point.theta);
      return thetas;
    };
    eq.indicator = {nf_, positions(closureLambdas(element - 1)), positions(closureLambdas(element)),
                    positions(stage_thetas(element - 1)), positions(stage_thetas(element))};
    for (int start : blocks) {
      for (int i = 0; i < nf_; ++i) eq.inputs.push_back(start + i);
    }
    eq.relaxed_row = nlp_.addRelaxedRows(1, options_.filippov.equilibration_relaxation);
    nlp_.addFunctionTerm(
        std::make_shared<StepEquilibrationResidual>(
            eq.indicator, nominalStep(element),
            options_.filippov.step_equilibration == StepEquilibration::kTanhIndicator),
        eq.inputs, -1, {{eq.relaxed_row, 1.0}});
    addStepRegularizer(nlp_, options_, nominalStep(element), eq.inputs[0], eq.inputs[1]);
    equilibration_.push_back(eq);
  }
  for (Equilibration& eq : equilibration_) eq.equal_steps_row = addEqualStepsRow(eq.element);
  nlp_.setActiveSetHook([this](const double*) { equilibrateActiveSet(); });
}

void StewartDiscretization::equilibrateActiveSet() {
  for (const Equilibration& eq : equilibration_) {
    auto nonzero = [&](const std::vector<int>& positions, int mode) {
      for (int p : positions) {
        if (!nlp_.fixedAtAboutZero(eq.inputs[2 + p * nf_ + mode])) return true;
      }
      return false;
    };
    const SwitchIndicator& sums = eq.indicator;
    bool indicator_positive = true;
    for (int i = 0; i < nf_; ++i) {
      indicator_positive &= (nonzero(sums.lambda_backward, i) && nonzero(sums.lambda_forward, i)) ||
                            (nonzero(sums.theta_backward, i) && nonzero(sums.theta_forward, i));
    }
    nlp_.setRowBounds(eq.relaxed_row, -kInf, kInf);
    if (indicator_positive) nlp_.setRowBounds(eq.equal_steps_row, 0.0, 0.0);
  }
}

std::vector<double> StewartDiscretization::switchIndicators(const double* x) const {
  std::vector<double> indicators;
  for (const Equilibration& eq : equilibration_) {
    std::vector<double> blocks;
    for (size_t v = 2; v < eq.inputs.size(); ++v) blocks.push_back(x[eq.inputs[v]]);
    indicators.push_back(eq.indicator(blocks.data()));
  }
  return indicators;
}

void StewartDiscretization::setInitialState(const Eigen::VectorXd& x0) {
  fixStartState(x0);
}

void StewartDiscretization::releaseInitialState() {
  if (!ocp_.initial_state_lower.size()) {
    throw std::logic_error("releaseInitialState: the OCP has no initial state bounds");
  }
  for (int d = 0; d < nx_; ++d) {
    nlp_.setVariableBounds(start_state_ + d, ocp_.initial_state_lower(d),
                           ocp_.initial_state_upper(d));
  }
}

void StewartDiscretization::setLpMultipliers(std::vector<double>& x, int state, int lambda,
                                             int mu) const {
  model_->lpMultipliers(x.data() + state, x.data() + lambda, x.data() + mu);
}

void StewartDiscretization::completeDependentVariables(std::vector<double>& x) const {
  if (!steps_free_) return;
  for (int e = 0; e < numElements(); ++e) {
    if (e > 0 && stage_at_end_) continue;  // a stage point, not a boundary point of its own
    const Element& element = elements_[e];
    setLpMultipliers(x, element.start_state, element.start.lambda, element.start.mu);
  }
  if (!stage_at_end_) {
    setLpMultipliers(x, elements_.back().end_state, final_boundary_.lambda, final_boundary_.mu);
  }
}

void StewartDiscretization::setModeOfState(std::vector<double>& x, const StagePoint& point) const {
  setLpMultipliers(x, point.x, point.lambda, point.mu);
  std::fill(x.begin() + point.theta, x.begin() + point.theta + nf_, 0.0);
  for (int k = 0, first = 0; k < nsys_; first += model_->modesPerSubsystem()[k], ++k) {
    const auto begin = x.begin() + point.lambda + first;
    const auto active = std::min_element(begin, begin + model_->modesPerSubsystem()[k]);
    x[point.theta + first + (active - begin)] = 1.0;
  }
}

std::vector<double> StewartDiscretization::constantGuess(
    const std::vector<Eigen::VectorXd>& controls) const {
  std::vector<double> x = nlp_.initialGuess();  // holds the start state
  const auto start = x.begin() + start_state_;
  for (int e = 0; e < numElements(); ++e) {
    const Element& element = elements_[e];
    std::copy(start, start + nx_, x.begin() + element.end_state);
    for (const StagePoint& point : element.stages) {
      std::copy(start, start + nx_, x.begin() + point.x);
      setModeOfState(x, point);
    }
    x[grid_.steps[e]] = nominalStep(e);
  }
  guessControls(nlp_, grid_, nu_, controls, x);
  completeDependentVariables(x);
  return x;
}

std::vector<double> StewartDiscretization::guessFrom(const TrajectoryGuess& guess) const {
  std::vector<double> x = nlp_.initialGuess();  // holds the start state
  guessGridPoints(nlp_, grid_, tableau_, nx_, nu_, guess, x);
  setModesOfStates(x);
  completeDependentVariables(x);
  return x;
}

void StewartDiscretization::guessPairValues(const Trajectory&, std::vector<double>& x) const {
  setModesOfStates(x);
}

void StewartDiscretization::setModesOfStates(std::vector<double>& x) const {
  for (const Element& element : elements_) {
    for (const StagePoint& point : element.stages) setModeOfState(x, point);
  }
}

std::vector<double> StewartDiscretization::translatedGuess(
    const std::vector<double>& previous_solution) const {
  requireOwnSize(previous_solution, "translatedGuess");
  // The states move with the start; the modes are those of the moved states and the grid is
  // uniform again: a switch inside the previous step says nothing about this one's.
  std::vector<double> x = previous_solution;
  Eigen::Map<Eigen::VectorXd> start(x.data() + start_state_, nx_);
  const Eigen::VectorXd shift =
      Eigen::Map<const Eigen::VectorXd>(nlp_.initialGuess().data() + start_state_, nx_) - start;
  start += shift;
  for (int e = 0; e < numElements(); ++e) {
    const Element& element = elements_[e];
    for (const StagePoint& point : element.stages) {
      Eigen::Map<Eigen::VectorXd>(x.data() + point.x, nx_) += shift;
      setModeOfState(x, point);
    }
    if (!stage_at_end_) Eigen::Map<Eigen::VectorXd>(x.data() + element.end_state, nx_) += shift;
    x[grid_.steps[e]] = nominalStep(e);
  }
  completeDependentVariables(x);
  return x;
}

void StewartDiscretization::readPairValues(const double* x, Trajectory& trajectory) const {
  for (int e = 0; e < numElements(); ++e) {
    ElementValues& values = trajectory.elements[e];
    for (int j = 0; j < tableau_.stages; ++j) {
      const StagePoint& point = elements_[e].stages[j];
      values.stage_multipliers.col(j) = Eigen::Map<const Eigen::VectorXd>(x + point.theta, nf_);
      values.stage_constraints.col(j) = Eigen::Map<const Eigen::VectorXd>(x + point.lambda, nf_);
    }
  }
}

std::vector<bool> StewartDiscretization::activeAtStart(const double*, const Trajectory& trajectory,
                                                       double tolerance) const {
  return activeAt(trajectory.states.front(), tolerance);
}

void StewartDiscretization::switchPair(PairModes& modes, int pair, int boundary,
                                       bool was_active) const {
  CollocationDiscretization::switchPair(modes, pair, boundary, was_active);
  if (was_active) return;
  const std::vector<bool> before = modes[boundary];
  for (int i = 0; i < nf_; ++i) {
    if (i == pair || model_->subsystemOf(i) != model_->subsystemOf(pair) || !before[i]) continue;
    CollocationDiscretization::switchPair(modes, i, boundary, true);
  }
}

std::vector<bool> StewartDiscretization::activeAt(const Eigen::VectorXd& x,
                                                  double tolerance) const {
  Eigen::VectorXd lambda(nf_), mu(nsys_);
  model_->lpMultipliers(x.data(), lambda.data(), mu.data());
  std::vector<bool> active(nf_);
  for (int i = 0; i < nf_; ++i) active[i] = lambda(i) <= tolerance;
  return active;
}

// Defined here, not with the model, so that models stay below the discretisation layer.
std::unique_ptr<Discretization> StewartModel::discretize(
    const OcpDefinition& ocp, const DiscretizationOptions& options) const {
  return std::make_unique<StewartDiscretization>(ocp, options);
}

}  // namespace fesd
