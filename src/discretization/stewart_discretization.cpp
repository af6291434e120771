#include "fesd_trajopt/discretization/stewart_discretization.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace fesd {
namespace {

constexpr double kInf = NlpAssembly::kInfinity;

/// ((h_n - h_{n-1}) / h0) * eta on z = (h_{n-1}, h_n, the indicator's blocks), or with
/// tanh(eta) (seed 001, eq. 31). Every NLP variable enters z once.
struct EquilibrationResidual {
  SwitchIndicator indicator;
  double h0;
  bool tanh_scaled;

  template <class T>
  void operator()(const T* z, T* r) const {
    using std::exp;
    T eta = indicator(z + 2);
    // tanh(eta) for eta >= 0 (sums of nonnegative variables), by exp alone.
    if (tanh_scaled) eta = (1.0 - exp(-2.0 * eta)) / (1.0 + exp(-2.0 * eta));
    r[0] = (z[1] - z[0]) * (1.0 / h0) * eta;
  }
};

}  // namespace

StewartDiscretization::StewartDiscretization(OcpDefinition ocp, DiscretizationOptions options)
    : ocp_(std::move(ocp)),
      model_(std::dynamic_pointer_cast<const StewartModel>(ocp_.model)),
      options_(options),
      tableau_(makeTableau(options.family, options.num_stages)) {
  if (!model_) throw std::invalid_argument("StewartDiscretization: the model is no StewartModel");
  validateOcp(ocp_, options_);
  nx_ = model_->stateSize();
  nu_ = model_->controlSize();
  nf_ = model_->numModes();
  nsys_ = model_->numSubsystems();
  nominal_step_ = fesd::nominalStep(ocp_, options_);
  steps_free_ = options_.switch_detection;
  stage_at_end_ = tableau_.lastStageIsEndPoint();
  buildVariables();
  buildDynamics();
  buildBoundaryPoints();
  buildComplementarity();
  buildStepEquilibration();
  addCostsAndConstraints(nlp_, grid_, ocp_, tableau_);
  nlp_.finalize();
}

void StewartDiscretization::buildVariables() {
  start_state_ = nlp_.addVariables(nx_, -kInf, kInf);
  if (ocp_.initial_state_lower.size()) {
    releaseInitialState();
    for (int d = 0; d < nx_; ++d) nlp_.initialGuess()[start_state_ + d] = ocp_.initial_state(d);
  } else {
    setInitialState(ocp_.initial_state);
  }
  const double step_lower =
      steps_free_ ? (1.0 - options_.step_bound) * nominal_step_ : nominal_step_;
  const double step_upper =
      steps_free_ ? (1.0 + options_.step_bound) * nominal_step_ : nominal_step_;
  auto add_state = [&] {
    const int x = nlp_.addVariables(nx_, -kInf, kInf);
    for (int d = 0; d < nx_; ++d) {
      nlp_.setVariableBounds(x + d, ocp_.state_lower.size() ? ocp_.state_lower(d) : -kInf,
                             ocp_.state_upper.size() ? ocp_.state_upper(d) : kInf);
    }
    return x;
  };
  grid_.elements_per_interval = options_.num_elements;
  for (int k = 0; k < ocp_.num_intervals; ++k) {
    grid_.controls.push_back(nlp_.addVariables(nu_, -kInf, kInf));
    fesd::freeControl(nlp_, grid_, ocp_, k);
    for (int n = 0; n < options_.num_elements; ++n) {
      grid_.steps.push_back(nlp_.addVariables(1, step_lower, step_upper, nominal_step_));
      Element element;
      element.start_state = elements_.empty() ? start_state_ : elements_.back().end_state;
      for (int j = 0; j < tableau_.stages; ++j) {
        StagePoint point;
        point.x = add_state();
        point.theta = nlp_.addVariables(nf_, 0.0, kInf);
        point.lambda = nlp_.addVariables(nf_, 0.0, kInf);
        point.mu = nlp_.addVariables(nsys_, -kInf, kInf);
        element.stages.push_back(point);
      }
      element.end_state = stage_at_end_ ? element.stages.back().x : add_state();
      grid_.stage_states.emplace_back();
      for (const StagePoint& point : element.stages) grid_.stage_states.back().push_back(point.x);
      grid_.end_states.push_back(element.end_state);
      elements_.push_back(element);
    }
  }
  core_variables_ = nlp_.numVariables();
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
  const int ns = tableau_.stages;
  for (int e = 0; e < numElements(); ++e) {
    const Element& element = elements_[e];
    // x_{n,i} - x_{n,0} - h_n sum_j a_ij v_j = 0, and for c_ns != 1 the end state with b_j
    const int first_row = nlp_.addRows(ns * nx_, 0.0, 0.0);
    const int end_row = stage_at_end_ ? -1 : nlp_.addRows(nx_, 0.0, 0.0);
    auto add_state_difference = [&](int row, int state) {
      for (int d = 0; d < nx_; ++d) {
        nlp_.addLinear(row + d, state + d, 1.0);
        nlp_.addLinear(row + d, element.start_state + d, -1.0);
      }
    };
    for (int i = 0; i < ns; ++i) add_state_difference(first_row + i * nx_, element.stages[i].x);
    if (end_row >= 0) add_state_difference(end_row, element.end_state);
    for (int j = 0; j < ns; ++j) {
      std::vector<NlpAssembly::Target> targets;
      for (int i = 0; i < ns; ++i) {
        if (tableau_.a(i, j) != 0.0) targets.push_back({first_row + i * nx_, -tableau_.a(i, j)});
      }
      if (end_row >= 0) targets.push_back({end_row, -tableau_.b(j)});
      const StagePoint& point = element.stages[j];
      std::vector<int> inputs = stateControlInputs(grid_, point.x, e, nx_, nu_);
      for (int i = 0; i < nf_; ++i) inputs.push_back(point.theta + i);
      nlp_.addFunctionTerm(model_->velocity(), inputs, grid_.steps[e], targets);
    }
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
          nlp_.addComplementarity({{point.theta + i, 1.0}}, {{point.lambda + i, 1.0}});
        }
        continue;
      }
      // Cross-complementarity (eq. 28): every stage theta_i of the element against every
      // lambda_i of its closure, as one product of sums or pair by pair.
      LinearExpression theta_side, lambda_side;
      for (const StagePoint& point : element.stages) theta_side.push_back({point.theta + i, 1.0});
      for (int lambda : closureLambdas(e)) lambda_side.push_back({lambda + i, 1.0});
      if (options_.cross_complementarity == CrossComplementarity::kElementSums) {
        nlp_.addComplementarity(theta_side, lambda_side);
        continue;
      }
      for (const LinearTerm& theta : theta_side) {
        for (const LinearTerm& lambda : lambda_side) nlp_.addComplementarity({theta}, {lambda});
      }
    }
  }
}

void StewartDiscretization::buildStepEquilibration() {
  if (!steps_free_ || options_.filippov.step_equilibration == StepEquilibration::kNone) return;
  for (int k = 0; k < ocp_.num_intervals; ++k) {
    for (int n = 1; n < options_.num_elements; ++n) {
      const int element = k * options_.num_elements + n;
      Equilibration eq;
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
      eq.indicator = {nf_, positions(closureLambdas(element - 1)),
                      positions(closureLambdas(element)), positions(stage_thetas(element - 1)),
                      positions(stage_thetas(element))};
      for (int start : blocks) {
        for (int i = 0; i < nf_; ++i) eq.inputs.push_back(start + i);
      }
      const EquilibrationResidual residual{
          eq.indicator, nominal_step_,
          options_.filippov.step_equilibration == StepEquilibration::kTanhIndicator};
      eq.relaxed_row = nlp_.addRelaxedRows(1, options_.filippov.equilibration_relaxation);
      nlp_.addFunctionTerm(makeAutoDiffFunction(static_cast<int>(eq.inputs.size()), 1, residual),
                           eq.inputs, -1, {{eq.relaxed_row, 1.0}});
      addStepRegularizer(nlp_, options_, nominal_step_, eq.inputs[0], eq.inputs[1]);
      equilibration_.push_back(eq);
    }
  }
  for (Equilibration& eq : equilibration_) {
    eq.equal_steps_row = nlp_.addRows(1, -kInf, kInf);
    nlp_.addLinear(eq.equal_steps_row, {{eq.inputs[0], 1.0}, {eq.inputs[1], -1.0}});
  }
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
  if (x0.size() != nx_) throw std::invalid_argument("initial state has the wrong size");
  ocp_.initial_state = x0;
  for (int d = 0; d < nx_; ++d) {
    nlp_.setVariableBounds(start_state_ + d, x0(d), x0(d));
    nlp_.initialGuess()[start_state_ + d] = x0(d);
  }
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

void StewartDiscretization::fixControl(int interval, const Eigen::VectorXd& u) {
  if (u.size() != nu_) throw std::invalid_argument("control has the wrong size");
  fesd::fixControl(nlp_, grid_, interval, u);
}

void StewartDiscretization::setLpMultipliers(std::vector<double>& x, int state, int lambda,
                                             int mu) const {
  model_->lpMultipliers(x.data() + state, x.data() + lambda, x.data() + mu);
}

void StewartDiscretization::completeBoundaryPoints(std::vector<double>& x) const {
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
    x[grid_.steps[e]] = nominal_step_;
  }
  guessControls(nlp_, grid_, nu_, controls, x);
  completeBoundaryPoints(x);
  return x;
}

std::vector<double> StewartDiscretization::guessFrom(const TrajectoryGuess& guess) const {
  std::vector<double> x = nlp_.initialGuess();  // holds the start state
  guessGridPoints(nlp_, grid_, tableau_, nominal_step_, nx_, nu_, guess, x);
  for (const Element& element : elements_) {
    for (const StagePoint& point : element.stages) setModeOfState(x, point);
  }
  completeBoundaryPoints(x);
  return x;
}

std::vector<double> StewartDiscretization::translatedGuess(
    const std::vector<double>& previous_solution) const {
  if (static_cast<int>(previous_solution.size()) != nlp_.numVariables()) {
    throw std::invalid_argument("translatedGuess: solution of a differently sized problem");
  }
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
    x[grid_.steps[e]] = nominal_step_;
  }
  completeBoundaryPoints(x);
  return x;
}

std::vector<double> StewartDiscretization::adoptedGuess(const Discretization& other_discretization,
                                                        const std::vector<double>& solution) const {
  const auto* other = dynamic_cast<const StewartDiscretization*>(&other_discretization);
  if (!other || other->core_variables_ != core_variables_ ||
      other->numElements() != numElements() || other->tableau_.stages != tableau_.stages ||
      static_cast<int>(solution.size()) != other->nlp_.numVariables()) {
    throw std::invalid_argument("adoptedGuess: the discretisations' grids differ");
  }
  std::vector<double> x = constantGuess();
  std::copy(solution.begin(), solution.begin() + core_variables_, x.begin());
  completeBoundaryPoints(x);
  return x;
}

Trajectory StewartDiscretization::extract(const double* x, double start_time,
                                          double activity_tolerance,
                                          double penetration_tolerance) const {
  Trajectory trajectory = gridTrajectory(x, grid_, ocp_, start_state_, nf_, start_time);
  for (int e = 0; e < numElements(); ++e) {
    ElementValues& values = trajectory.elements[e];
    for (int j = 0; j < tableau_.stages; ++j) {
      const StagePoint& point = elements_[e].stages[j];
      values.stage_multipliers.col(j) = Eigen::Map<const Eigen::VectorXd>(x + point.theta, nf_);
      values.stage_constraints.col(j) = Eigen::Map<const Eigen::VectorXd>(x + point.lambda, nf_);
    }
  }
  classifySwitches(trajectory, activeAt(trajectory.states.front(), activity_tolerance),
                   activity_tolerance, penetration_tolerance);
  return trajectory;
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
