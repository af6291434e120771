#include "fesd_trajopt/discretization/collocation_discretization.h"

#include <algorithm>
#include <stdexcept>
#include <string>
#include <typeinfo>

namespace fesd {
namespace {

constexpr double kInf = NlpAssembly::kInfinity;

}  // namespace

CollocationDiscretization::CollocationDiscretization(OcpDefinition ocp,
                                                     DiscretizationOptions options)
    : ocp_(std::move(ocp)),
      options_(options),
      tableau_(makeTableau(options.family, options.num_stages)) {
  validateOcp(ocp_, options_);
  nx_ = ocp_.model->stateSize();
  nu_ = ocp_.model->controlSize();
  grid_ = elementLayout(ocp_, options_);
}

void CollocationDiscretization::fixControl(int interval, const Eigen::VectorXd& u) {
  if (u.size() != nu_) throw std::invalid_argument("control has the wrong size");
  fesd::fixControl(nlp_, grid_, interval, u);
}

void CollocationDiscretization::freeControl(int interval) {
  fesd::freeControl(nlp_, grid_, ocp_, interval);
}

std::vector<double> CollocationDiscretization::adoptedGuess(
    const Discretization& other_discretization, const std::vector<double>& solution) const {
  const auto* other = dynamic_cast<const CollocationDiscretization*>(&other_discretization);
  if (!other || typeid(*other) != typeid(*this) || other->core_variables_ != core_variables_ ||
      other->numElements() != numElements() || other->tableau_.stages != tableau_.stages ||
      static_cast<int>(solution.size()) != other->nlp_.numVariables()) {
    throw std::invalid_argument("adoptedGuess: the discretisations' grids differ");
  }
  std::vector<double> x = constantGuess();
  std::copy(solution.begin(), solution.begin() + core_variables_, x.begin());
  completeDependentVariables(x);
  return x;
}

std::vector<double> CollocationDiscretization::guessFromTrajectory(
    const Trajectory& trajectory) const {
  const bool sizes_match = static_cast<int>(trajectory.elements.size()) == numElements() &&
                           static_cast<int>(trajectory.states.size()) == numElements() + 1 &&
                           trajectory.controls.size() == grid_.controls.size() &&
                           std::all_of(trajectory.elements.begin(), trajectory.elements.end(),
                                       [&](const ElementValues& element) {
                                         return element.stage_states.rows() == nx_ &&
                                                element.stage_states.cols() == tableau_.stages &&
                                                element.stage_multipliers.rows() == numPairs();
                                       });
  if (!sizes_match) {
    throw std::invalid_argument("guessFromTrajectory: the trajectory's grid or sizes differ");
  }
  std::vector<double> x = nlp_.initialGuess();  // holds the start point's data
  for (int e = 0; e < numElements(); ++e) {
    const ElementValues& element = trajectory.elements[e];
    const int step = grid_.steps[e];
    x[step] = std::clamp(element.step, nlp_.variableLower(step), nlp_.variableUpper(step));
    for (int i = 0; i < tableau_.stages; ++i) {
      Eigen::Map<Eigen::VectorXd>(x.data() + grid_.stage_states[e][i], nx_) =
          element.stage_states.col(i);
    }
    Eigen::Map<Eigen::VectorXd>(x.data() + grid_.end_states[e], nx_) = trajectory.states[e + 1];
  }
  guessControls(nlp_, grid_, nu_, trajectory.controls, x);
  guessPairValues(trajectory, x);
  completeDependentVariables(x);
  return x;
}

Trajectory CollocationDiscretization::extract(const double* x, double start_time,
                                              double activity_tolerance,
                                              double penetration_tolerance) const {
  Trajectory trajectory = gridTrajectory(x, grid_, ocp_, start_state_, numPairs(), start_time);
  trajectory.stage_nodes = tableau_.c;
  readPairValues(x, trajectory);
  classifySwitches(trajectory, activeAtStart(x, trajectory, activity_tolerance), activity_tolerance,
                   penetration_tolerance);
  return trajectory;
}

std::vector<bool> CollocationDiscretization::activeSetOf(const PairModes& modes) const {
  if (static_cast<int>(pair_origins_.size()) != nlp_.numComplementarities()) return {};
  std::vector<bool> left_is_zero;
  for (const PairOrigin& origin : pair_origins_) {
    const bool active = modes.at(origin.element).at(origin.pair);
    left_is_zero.push_back(active == origin.left_is_constraint);
  }
  return left_is_zero;
}

void CollocationDiscretization::switchPair(PairModes& modes, int pair, int boundary,
                                           bool was_active) const {
  for (size_t e = boundary; e < modes.size(); ++e) modes[e][pair] = !was_active;
}

void CollocationDiscretization::addPairComplementarity(int element, int pair,
                                                       const LinearExpression& left,
                                                       const LinearExpression& right,
                                                       bool left_is_constraint, double left_weight,
                                                       double right_weight) {
  nlp_.addComplementarity(left, right, left_weight, right_weight);
  pair_origins_.push_back({element, pair, left_is_constraint});
}

void CollocationDiscretization::addStartState() {
  start_state_ = nlp_.addVariables(nx_, -kInf, kInf);
}

std::vector<int> CollocationDiscretization::startAndControlVariables() const {
  std::vector<int> variables;
  for (int d = 0; d < nx_; ++d) variables.push_back(start_state_ + d);
  for (int d = 0; d < nu_; ++d) variables.push_back(grid_.controls.front() + d);
  return variables;
}

void CollocationDiscretization::fixStartState(const Eigen::VectorXd& x0) {
  if (x0.size() != nx_) throw std::invalid_argument("initial state has the wrong size");
  ocp_.initial_state = x0;
  for (int d = 0; d < nx_; ++d) {
    nlp_.setVariableBounds(start_state_ + d, x0(d), x0(d));
    nlp_.initialGuess()[start_state_ + d] = x0(d);
  }
}

int CollocationDiscretization::addStateVariables() {
  const int x = nlp_.addVariables(nx_, -kInf, kInf);
  for (int d = 0; d < nx_; ++d) {
    nlp_.setVariableBounds(x + d, ocp_.state_lower.size() ? ocp_.state_lower(d) : -kInf,
                           ocp_.state_upper.size() ? ocp_.state_upper(d) : kInf);
  }
  return x;
}

int CollocationDiscretization::elementStartState(int element) const {
  return element == 0 ? start_state_ : grid_.end_states[element - 1];
}

void CollocationDiscretization::addRungeKuttaRows(
    int element, const std::shared_ptr<const SmoothFunction>& velocity,
    const std::vector<int>& stage_blocks, int block_size) {
  const int ns = tableau_.stages;
  const std::vector<int>& stages = grid_.stage_states[element];
  const int start = elementStartState(element), end = grid_.end_states[element];
  const bool end_is_stage = end == stages.back();
  const int first_row = nlp_.addRows(ns * nx_, 0.0, 0.0);
  const int end_row = end_is_stage ? -1 : nlp_.addRows(nx_, 0.0, 0.0);
  auto add_state_difference = [&](int row, int state) {
    for (int d = 0; d < nx_; ++d) {
      nlp_.addLinear(row + d, state + d, 1.0);
      nlp_.addLinear(row + d, start + d, -1.0);
    }
  };
  for (int i = 0; i < ns; ++i) add_state_difference(first_row + i * nx_, stages[i]);
  if (end_row >= 0) add_state_difference(end_row, end);
  for (int j = 0; j < ns; ++j) {
    std::vector<NlpAssembly::Target> targets;
    for (int i = 0; i < ns; ++i) {
      if (tableau_.a(i, j) != 0.0) targets.push_back({first_row + i * nx_, -tableau_.a(i, j)});
    }
    if (end_row >= 0) targets.push_back({end_row, -tableau_.b(j)});
    std::vector<int> inputs = stateControlInputs(grid_, stages[j], element, nx_, nu_);
    for (int i = 0; i < block_size; ++i) inputs.push_back(stage_blocks[j] + i);
    nlp_.addFunctionTerm(velocity, inputs, grid_.steps[element], targets);
  }
}

std::vector<int> CollocationDiscretization::innerBoundaries() const {
  std::vector<int> elements;
  for (int e = 1; e < numElements(); ++e) {
    if (!grid_.startsInterval(e)) elements.push_back(e);
  }
  return elements;
}

int CollocationDiscretization::addEqualStepsRow(int element) {
  const int row = nlp_.addRows(1, -kInf, kInf);
  nlp_.addLinear(row, {{grid_.steps[element - 1], 1.0}, {grid_.steps[element], -1.0}});
  return row;
}

void CollocationDiscretization::requireOwnSize(const std::vector<double>& solution,
                                               const char* caller) const {
  if (static_cast<int>(solution.size()) != nlp_.numVariables()) {
    throw std::invalid_argument(std::string(caller) + ": solution of a differently sized problem");
  }
}

}  // namespace fesd
