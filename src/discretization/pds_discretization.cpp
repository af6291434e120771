#include "fesd_trajopt/discretization/pds_discretization.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <tuple>

#include "fesd_trajopt/function/combination_row.h"

namespace fesd {
namespace {

constexpr double kInf = NlpAssembly::kInfinity;

}  // namespace

PdsDiscretization::PdsDiscretization(OcpDefinition ocp, DiscretizationOptions options)
    : CollocationDiscretization(std::move(ocp), options),
      model_(std::dynamic_pointer_cast<const DcsModel>(ocp_.model)) {
  if (!model_) throw std::invalid_argument("PdsDiscretization: the model is not a DcsModel");
  if (ocp_.initial_state_lower.size()) {
    throw std::invalid_argument("PdsDiscretization: a free initial state is not supported");
  }
  nc_ = model_->constraintSize();
  if (!tableau_.lastStageIsEndPoint()) {
    throw std::invalid_argument("PdsDiscretization: scheme " + tableau_.name() +
                                " has no stage at the element end (c_ns != 1); use Radau-IIA");
  }
  // Without constraints nothing can switch: the steps stay fixed and no MPCC machinery is built.
  steps_free_ = options_.switch_detection && nc_ > 0;
  buildVariables();
  buildDynamics();
  buildComplementarity();
  buildStepEquilibration();
  buildGapGuards();
  buildForceConstraints();
  addCostsAndConstraints(nlp_, grid_, ocp_, tableau_);
  nlp_.finalize();
  nlp_.setEvaluationThreads(options_.evaluation_threads);
}

void PdsDiscretization::buildVariables() {
  addStartState();
  // c(x_start) is data (x_start is fixed): set by setInitialState, without a sign bound, so that
  // a start a rounding error inside the boundary (the end of a previous step) stays feasible.
  start_.s = nlp_.addVariables(nc_, 0.0, 0.0);
  // lambda just before the start (data: 0, or the end of a previous simulation step). It only
  // enters the step-equilibration sums.
  start_.lambda = nlp_.addVariables(nc_, 0.0, 0.0);
  carried_lambda_ = nlp_.addVariables(nc_, 0.0, 0.0);
  setInitialState(ocp_.initial_state);
  buildGrid([&](int) {
    std::vector<StagePoint> points(tableau_.stages);
    ElementStates states;
    for (StagePoint& point : points) {
      point.x = addStateVariables();
      point.s = nlp_.addVariables(nc_, 0.0, kInf);
      point.lambda = nlp_.addVariables(nc_, 0.0, kInf);
      states.stages.push_back(point.x);
    }
    states.end = points.back().x;
    stages_.push_back(points);
    return states;
  });
}

const PdsDiscretization::StagePoint& PdsDiscretization::previousPoint(int element) const {
  return element == 0 ? start_ : stages_[element - 1].back();
}

std::vector<int> PdsDiscretization::jumpingForces(const PairModes& modes) const {
  std::vector<int> forces;
  if (!steps_free_) return forces;
  const int elements = std::min(numElements(), static_cast<int>(modes.size()));
  // At a control interval's start the force before is no part of the cross-complementarity.
  for (int e = 1; e < elements; ++e) {
    if (startsInterval(e)) continue;
    bool contact = false;
    for (int k = 0; k < nc_; ++k) contact = contact || (!modes[e - 1][k] && modes[e][k]);
    if (!contact) continue;
    for (int k = 0; k < nc_; ++k) {
      if (modes[e - 1][k] && !modes[e][k]) forces.push_back(previousPoint(e).lambda + k);
    }
  }
  return forces;
}

void PdsDiscretization::addLifting(const StagePoint& point) {
  if (nc_ == 0) return;
  const int row = nlp_.addRows(nc_, 0.0, 0.0);
  for (int k = 0; k < nc_; ++k) nlp_.addLinear(row + k, point.s + k, 1.0);
  std::vector<int> inputs;
  for (int d = 0; d < nx_; ++d) inputs.push_back(point.x + d);
  nlp_.addFunctionTerm(model_->constraints(), inputs, -1, {{row, -1.0}});
}

void PdsDiscretization::buildDynamics() {
  for (int e = 0; e < numElements(); ++e) {
    std::vector<int> multipliers;
    for (const StagePoint& point : stages_[e]) multipliers.push_back(point.lambda);
    addRungeKuttaRows(e, model_->velocity(), multipliers, nc_);
    for (const StagePoint& point : stages_[e]) addLifting(point);
  }
  if (steps_free_) addIntervalLengthRows(nlp_, grid_, ocp_);
}

void PdsDiscretization::buildComplementarity() {
  const int ns = tableau_.stages;
  for (int e = 0; e < numElements(); ++e) {
    for (int k = 0; k < nc_; ++k) {
      // Decisions compare c / |grad c| (distance to the boundary) with h0 lambda |grad c| (the
      // distance the force moves in an element): at R = 1e-3 raw c (~1e-7) looked smaller than
      // a free pair's relaxed lambda (~1e-3), and polishing fixed contacts that were not there.
      const double scale = model_->constraintScales()(k);
      const double c_weight = 1.0 / scale, lambda_weight = nominalStep(e) * scale;
      if (!steps_free_) {
        for (const StagePoint& point : stages_[e]) {
          addPairComplementarity(e, k, {{point.s + k, 1.0}}, {{point.lambda + k, 1.0}}, true,
                                 c_weight, lambda_weight);
        }
        continue;
      }
      // Cross-complementarity (eq. 8): c at the element's stage points and at the previous
      // boundary point against lambda at the stage points and at the previous element's last
      // stage. The latter only within a control interval: a control jump may release a contact
      // with a jump of lambda, which eq. 8c (derived for continuous f) would forbid.
      const StagePoint& previous = previousPoint(e);
      const bool previous_lambda = !startsInterval(e);
      LinearExpression c_side{{previous.s + k, 1.0}}, lambda_side;
      for (int i = 0; i < ns; ++i) {
        c_side.push_back({stages_[e][i].s + k, 1.0});
        lambda_side.push_back({stages_[e][i].lambda + k, 1.0});
      }
      if (previous_lambda) lambda_side.push_back({previous.lambda + k, 1.0});
      if (e == 0) lambda_side.push_back({carried_lambda_ + k, 1.0});
      if (options_.cross_complementarity == CrossComplementarity::kElementSums) {
        addPairComplementarity(e, k, c_side, lambda_side, true, c_weight, lambda_weight);
        continue;
      }
      for (size_t a = 0; a < c_side.size(); ++a) {
        for (size_t b = 0; b < lambda_side.size(); ++b) {
          // The previous point's c against the previous point's lambda (or the carried one):
          // one point, no cross pair.
          const bool both_previous =
              a == 0 && (previous_lambda || e == 0) && b + 1 == lambda_side.size();
          if (!both_previous) {
            addPairComplementarity(e, k, {c_side[a]}, {lambda_side[b]}, true, c_weight,
                                   lambda_weight);
          }
        }
      }
    }
  }
}

void PdsDiscretization::buildGapGuards() {
  for (const GapGuard& guard : options_.gap_guards) {
    if (guard.element < 0 || guard.element >= numElements() || guard.constraint < 0 ||
        guard.constraint >= nc_ || !(guard.fraction > 0.0 && guard.fraction < 1.0)) {
      throw std::invalid_argument("PdsDiscretization: a gap guard outside the grid or the model");
    }
    const auto row = std::make_shared<CombinationRow>(
        model_->constraints(), guard.constraint, collocationWeights(tableau_.c, guard.fraction));
    std::vector<int> inputs;
    std::vector<int> points{elementStartState(guard.element)};
    for (const StagePoint& point : stages_[guard.element]) points.push_back(point.x);
    for (int point : points) {
      for (int coordinate : row->coordinates()) inputs.push_back(point + coordinate);
    }
    nlp_.addFunctionTerm(row, inputs, -1, {{nlp_.addRows(1, 0.0, kInf), 1.0}});
  }
}

void PdsDiscretization::buildForceConstraints() {
  const std::shared_ptr<const SmoothFunction>& forces = ocp_.force_constraints;
  if (!forces) return;
  const Eigen::VectorXd& upper = ocp_.force_upper;
  if (forces->inputSize() != nx_ + nu_ + nc_ ||
      (upper.size() != 0 && upper.size() != forces->outputSize())) {
    throw std::invalid_argument("OcpDefinition: force_constraints has the wrong size");
  }
  for (int e = 0; e < numElements(); ++e) {
    for (const StagePoint& point : stages_[e]) {
      std::vector<int> inputs = stateControlInputs(grid_, point.x, e, nx_, nu_);
      for (int k = 0; k < nc_; ++k) inputs.push_back(point.lambda + k);
      const int row = nlp_.addRows(forces->outputSize(), -kInf, 0.0);
      for (int r = 0; r < upper.size(); ++r) nlp_.setRowBounds(row + r, -kInf, upper(r));
      nlp_.addFunctionTerm(forces, inputs, -1, {{row, 1.0}});
    }
  }
}

void PdsDiscretization::buildStepEquilibration() {
  if (!steps_free_) return;
  // Sums over the points of an element's closure. The backward sums also take the element's start
  // point: with one Radau stage (the end point) the stage points alone carry no trace of a
  // contact or release at the element's end, and nu would vanish at every switch (Table I needs
  // c > 0 before a contact and lambda > 0 before a release). A larger sum can only make nu
  // larger, so this never forbids a switch that the paper's sums allow.
  auto closure_sum = [&](int element, int k, bool lambda, bool with_start) {
    LinearExpression sum;
    if (with_start) {
      const StagePoint& start = previousPoint(element);
      sum.push_back({(lambda ? start.lambda : start.s) + k, 1.0});
    }
    for (const StagePoint& point : stages_[element]) {
      sum.push_back({(lambda ? point.lambda : point.s) + k, 1.0});
    }
    return sum;
  };
  auxiliary_variables_begin_ = auxiliary_variables_end_ = nlp_.numVariables();
  auxiliary_rows_begin_ = auxiliary_rows_end_ = nlp_.numConstraints();
  for (int element : innerBoundaries()) {
    EquilibrationAuxiliaries boundary{element - 1, element, {}, {}, {}, {}, {}, {}, {}, -1, -1};
    for (int k = 0; k < nc_; ++k) {
      boundary.sums.push_back(
          {closure_sum(element - 1, k, true, true), closure_sum(element, k, true, false),
           closure_sum(element - 1, k, false, true), closure_sum(element, k, false, false)});
    }
    addStepRegularizer(nlp_, options_, nominalStep(element), grid_.steps[element - 1],
                       grid_.steps[element]);
    equilibration_.push_back(boundary);
  }
  if (options_.pds.step_equilibration == PdsStepEquilibration::kBigM) addBigMEquilibration();
  for (EquilibrationAuxiliaries& aux : equilibration_) {
    aux.equal_steps_row = addEqualStepsRow(aux.element);
  }
  nlp_.setActiveSetHook([this](const double* x) { equilibrateActiveSet(x); });
}

void PdsDiscretization::addBigMEquilibration() {
  auxiliary_variables_begin_ = nlp_.numVariables();
  auxiliary_rows_begin_ = nlp_.numConstraints();
  auto add_row = [&](const LinearExpression& expression, double lower, double upper) {
    const int row = nlp_.addRows(1, lower, upper);
    nlp_.addLinear(row, expression);
  };
  auto scaled = [](LinearExpression expression, double factor) {
    for (LinearTerm& t : expression) t.coefficient *= factor;
    return expression;
  };
  auto concat = [](LinearExpression a, const LinearExpression& b) {
    a.insert(a.end(), b.begin(), b.end());
    return a;
  };
  for (EquilibrationAuxiliaries& aux : equilibration_) {
    LinearExpression any_switch_upper;
    for (const BoundarySums& sums : aux.sums) {
      const int pi_lambda = nlp_.addVariables(1, 0.0, kInf);
      const int pi_c = nlp_.addVariables(1, 0.0, kInf);
      const int maximum = nlp_.addVariables(1, 0.0, kInf);
      const int gap = nlp_.addVariables(2, 0.0, kInf);      // max - pi_c, max - pi_lambda
      const int kkt = nlp_.addVariables(2, 0.0, 1.0, 0.5);  // LP multipliers of max
      const int nu = nlp_.addVariables(1, 0.0, kInf);
      // pi = backward v forward:  pi >= B, pi >= F, pi <= B + F
      const std::tuple<int, const LinearExpression&, const LinearExpression&> disjunctions[] = {
          {pi_lambda, sums.lambda_backward, sums.lambda_forward},
          {pi_c, sums.c_backward, sums.c_forward}};
      for (const auto& [pi, backward, forward] : disjunctions) {
        add_row(concat({{pi, 1.0}}, scaled(backward, -1.0)), 0.0, kInf);
        add_row(concat({{pi, 1.0}}, scaled(forward, -1.0)), 0.0, kInf);
        add_row(concat(concat({{pi, 1.0}}, scaled(backward, -1.0)), scaled(forward, -1.0)), -kInf,
                0.0);
      }
      // maximum = max(pi_c, pi_lambda) by the KKT conditions of min z s.t. z >= pi_c, pi_lambda:
      // gaps z - pi >= 0 (lifted, so every complementarity pair is between nonnegative
      // variables), multipliers summing to one, each complementary to its gap.
      add_row({{gap, 1.0}, {maximum, -1.0}, {pi_c, 1.0}}, 0.0, 0.0);
      add_row({{gap + 1, 1.0}, {maximum, -1.0}, {pi_lambda, 1.0}}, 0.0, 0.0);
      add_row({{kkt, 1.0}, {kkt + 1, 1.0}}, 1.0, 1.0);
      nlp_.addComplementarity({{gap, 1.0}}, {{kkt, 1.0}});
      nlp_.addComplementarity({{gap + 1, 1.0}}, {{kkt + 1, 1.0}});
      // nu = pi_c ^ pi_lambda:  nu <= pi_c, nu <= pi_lambda, nu >= pi_c + pi_lambda - max
      add_row({{nu, 1.0}, {pi_c, -1.0}}, -kInf, 0.0);
      add_row({{nu, 1.0}, {pi_lambda, -1.0}}, -kInf, 0.0);
      add_row({{nu, 1.0}, {pi_c, -1.0}, {pi_lambda, -1.0}, {maximum, 1.0}}, 0.0, kInf);
      aux.pi_lambda.push_back(pi_lambda);
      aux.pi_c.push_back(pi_c);
      aux.maximum.push_back(maximum);
      aux.gap.push_back(gap);
      aux.kkt.push_back(kkt);
      aux.nu.push_back(nu);
      any_switch_upper.push_back({nu, -1.0});
    }
    // OR over the constraints: nu_k <= eta <= sum_k nu_k
    aux.any_switch = nlp_.addVariables(1, 0.0, kInf);
    for (int nu : aux.nu) add_row({{aux.any_switch, 1.0}, {nu, -1.0}}, 0.0, kInf);
    add_row(concat({{aux.any_switch, 1.0}}, any_switch_upper), -kInf, 0.0);
    // -eta M <= h_{n-1} - h_n <= eta M
    const double big_m = options_.pds.equilibration_big_m * nominalStep(aux.element);
    const int h_prev = grid_.steps[aux.previous_element], h = grid_.steps[aux.element];
    add_row({{h_prev, 1.0}, {h, -1.0}, {aux.any_switch, -big_m}}, -kInf, 0.0);
    add_row({{h_prev, 1.0}, {h, -1.0}, {aux.any_switch, big_m}}, 0.0, kInf);
  }
  auxiliary_variables_end_ = nlp_.numVariables();
  auxiliary_rows_end_ = nlp_.numConstraints();
}

void PdsDiscretization::equilibrateActiveSet(const double* x) {
  // Frozen at values exactly consistent with the point (max, min, KKT multipliers in {0, 1}).
  std::vector<double> consistent(x, x + nlp_.numVariables());
  completeDependentVariables(consistent);
  for (int v = auxiliary_variables_begin_; v < auxiliary_variables_end_; ++v) {
    nlp_.setVariableBounds(v, consistent[v], consistent[v]);
  }
  for (int row = auxiliary_rows_begin_; row < auxiliary_rows_end_; ++row) {
    nlp_.setRowBounds(row, -kInf, kInf);
  }
  auto nonzero = [&](const LinearExpression& sum) {
    for (const LinearTerm& t : sum) {
      if (!nlp_.fixedAtAboutZero(t.variable)) return true;
    }
    return false;
  };
  for (const EquilibrationAuxiliaries& aux : equilibration_) {
    bool any_switch = false;
    for (const BoundarySums& sums : aux.sums) {
      any_switch |= (nonzero(sums.c_backward) || nonzero(sums.c_forward)) &&
                    (nonzero(sums.lambda_backward) || nonzero(sums.lambda_forward));
    }
    if (!any_switch) nlp_.setRowBounds(aux.equal_steps_row, 0.0, 0.0);
  }
}

void PdsDiscretization::setInitialState(const Eigen::VectorXd& x0) {
  fixStartState(x0);
  Eigen::VectorXd c0(nc_);
  model_->constraints()->evaluate(x0.data(), c0.data());
  for (int k = 0; k < nc_; ++k) {
    nlp_.setVariableBounds(start_.s + k, c0(k), c0(k));
    nlp_.initialGuess()[start_.s + k] = c0(k);
  }
}

void PdsDiscretization::setInitialMultipliers(const Eigen::VectorXd& lambda0) {
  if (lambda0.size() != nc_) throw std::invalid_argument("initial multipliers have the wrong size");
  for (int k = 0; k < nc_; ++k) {
    const double value = std::max(lambda0(k), 0.0);
    nlp_.setVariableBounds(start_.lambda + k, value, value);
    nlp_.initialGuess()[start_.lambda + k] = value;
  }
}

void PdsDiscretization::continueFrom(const Trajectory& previous, bool same_dynamics) {
  const Eigen::VectorXd lambda = previous.elements.back().stage_multipliers.rightCols(1);
  setInitialMultipliers(lambda);
  for (int k = 0; k < nc_; ++k) {
    // Only a pair in contact at the start carries its force: c0 lambda0 > 0 would make the
    // product row of the first element infeasible.
    const bool in_contact = nlp_.initialGuess()[start_.s + k] <= NlpAssembly::kNegligibleFixedValue;
    const double carried = same_dynamics && in_contact ? std::max(lambda(k), 0.0) : 0.0;
    nlp_.setVariableBounds(carried_lambda_ + k, carried, carried);
    nlp_.initialGuess()[carried_lambda_ + k] = carried;
  }
}

std::vector<double> PdsDiscretization::constantGuess(
    const std::vector<Eigen::VectorXd>& controls) const {
  std::vector<double> x = nlp_.initialGuess();  // holds the start point's data
  for (const auto& element : stages_) {
    for (const StagePoint& point : element) {
      for (int d = 0; d < nx_; ++d) x[point.x + d] = ocp_.initial_state(d);
      for (int k = 0; k < nc_; ++k) {
        x[point.s + k] = std::max(x[start_.s + k], 0.0);
        x[point.lambda + k] = 0.0;
      }
    }
  }
  for (int e = 0; e < numElements(); ++e) x[grid_.steps[e]] = nominalStep(e);
  guessControls(nlp_, grid_, nu_, controls, x);
  completeDependentVariables(x);
  return x;
}

std::vector<double> PdsDiscretization::guessFrom(const TrajectoryGuess& guess) const {
  std::vector<double> x = nlp_.initialGuess();  // holds the start point's data
  guessGridPoints(nlp_, grid_, tableau_, nx_, nu_, guess, x);
  for (int e = 0; e < numElements(); ++e) {
    for (int i = 0; i < tableau_.stages; ++i) {
      setPairGuess(stages_[e][i],
                   guess.multipliers ? guess.multipliers(nominalTime(grid_, e, tableau_.c(i)))
                                     : Eigen::VectorXd::Zero(nc_),
                   x);
    }
  }
  completeDependentVariables(x);
  return x;
}

void PdsDiscretization::guessPairValues(const Trajectory& trajectory,
                                        std::vector<double>& x) const {
  for (int e = 0; e < numElements(); ++e) {
    for (int i = 0; i < tableau_.stages; ++i) {
      setPairGuess(stages_[e][i], trajectory.elements[e].stage_multipliers.col(i), x);
    }
  }
}

void PdsDiscretization::setPairGuess(const StagePoint& point, const Eigen::VectorXd& lambda,
                                     std::vector<double>& x) const {
  if (lambda.size() != nc_) throw std::invalid_argument("guess: multipliers of the wrong size");
  model_->constraints()->evaluate(x.data() + point.x, x.data() + point.s);
  for (int k = 0; k < nc_; ++k) {
    x[point.s + k] = std::max(x[point.s + k], 0.0);
    x[point.lambda + k] = std::max(lambda(k), 0.0);
  }
}

std::vector<double> PdsDiscretization::translatedGuess(
    const std::vector<double>& previous_solution) const {
  requireOwnSize(previous_solution, "translatedGuess");
  std::vector<double> x = previous_solution;
  const Eigen::VectorXd shift =
      ocp_.initial_state - Eigen::Map<const Eigen::VectorXd>(x.data() + start_state_, nx_);
  auto move_point = [&](const StagePoint& point) {
    Eigen::Map<Eigen::VectorXd> state(x.data() + point.x, nx_);
    state += shift;
    model_->constraints()->evaluate(state.data(), x.data() + point.s);
  };
  for (const auto& element : stages_) {
    for (const StagePoint& point : element) move_point(point);
  }
  for (int i = 0; i < nx_; ++i) x[start_state_ + i] = nlp_.initialGuess()[start_state_ + i];
  for (int k = 0; k < nc_; ++k) {
    x[start_.s + k] = nlp_.initialGuess()[start_.s + k];
    x[start_.lambda + k] = nlp_.initialGuess()[start_.lambda + k];
  }
  completeDependentVariables(x);
  return x;
}

void PdsDiscretization::completeDependentVariables(std::vector<double>& x) const {
  auto value = [&](const LinearExpression& expression) {
    double total = 0.0;
    for (const LinearTerm& t : expression) total += t.coefficient * x[t.variable];
    return total;
  };
  for (const EquilibrationAuxiliaries& aux : equilibration_) {
    if (aux.any_switch < 0) continue;  // no big-M auxiliaries
    double any = 0.0;
    for (int k = 0; k < nc_; ++k) {
      const BoundarySums& sums = aux.sums[k];
      const double pi_lambda = std::max(value(sums.lambda_backward), value(sums.lambda_forward));
      const double pi_c = std::max(value(sums.c_backward), value(sums.c_forward));
      x[aux.pi_lambda[k]] = pi_lambda;
      x[aux.pi_c[k]] = pi_c;
      x[aux.maximum[k]] = std::max(pi_c, pi_lambda);
      x[aux.gap[k]] = std::max(pi_c, pi_lambda) - pi_c;
      x[aux.gap[k] + 1] = std::max(pi_c, pi_lambda) - pi_lambda;
      x[aux.kkt[k]] = pi_c >= pi_lambda ? 1.0 : 0.0;  // the LP multiplier of the larger side
      x[aux.kkt[k] + 1] = pi_c >= pi_lambda ? 0.0 : 1.0;
      x[aux.nu[k]] = std::min(pi_c, pi_lambda);
      any = std::max(any, x[aux.nu[k]]);
    }
    x[aux.any_switch] = any;
  }
}

void PdsDiscretization::readPairValues(const double* x, Trajectory& trajectory) const {
  for (int e = 0; e < numElements(); ++e) {
    ElementValues& element = trajectory.elements[e];
    for (int j = 0; j < tableau_.stages; ++j) {
      const StagePoint& point = stages_[e][j];
      element.stage_multipliers.col(j) = Eigen::Map<const Eigen::VectorXd>(x + point.lambda, nc_);
      element.stage_constraints.col(j) = Eigen::Map<const Eigen::VectorXd>(x + point.s, nc_);
    }
    if (nc_ > 0) {
      element.lowest_constraints = lowestConstraintBetweenStages(
          *model_->constraints(), tableau_.c, trajectory.states[e], element.stage_states);
    }
  }
}

namespace {

/// Closer than this fraction of an element to its start or end, a touch is the boundary's.
constexpr double kEndFraction = 1e-6;

}  // namespace

bool PdsDiscretization::grazesBetweenStages(const Trajectory& piece, int element, int pair,
                                            double tolerance) const {
  const ElementValues& values = piece.elements[element];
  // Between samples a distance can dip below the lowest sampled one by about its curvature
  // times (moved * sample spacing)^2 / 8: far below `moved`^2 for contact distances of 1 cm and
  // up. Farther than that, the search is not needed.
  const double moved =
      (values.stage_states.colwise() - piece.states[element]).colwise().norm().maxCoeff();
  if (values.lowest_constraints.size() > pair &&
      values.lowest_constraints(pair) > moved * moved + tolerance) {
    return false;
  }
  // A touch at the element's ends is a boundary point's, which the stage checks see.
  const ClosestApproach closest = closestApproach(*model_->constraints(), pair, tableau_.c,
                                                  piece.states[element], values.stage_states);
  return closest.distance <= tolerance && closest.fraction > kEndFraction &&
         closest.fraction < 1.0 - kEndFraction;
}

std::vector<bool> PdsDiscretization::activeAtStart(const double* x, const Trajectory&,
                                                   double tolerance) const {
  std::vector<bool> active(nc_);
  for (int k = 0; k < nc_; ++k) active[k] = x[start_.s + k] <= tolerance;
  return active;
}

std::vector<bool> PdsDiscretization::activeAt(const Eigen::VectorXd& x, double tolerance) const {
  Eigen::VectorXd c(nc_);
  model_->constraints()->evaluate(x.data(), c.data());
  std::vector<bool> active(nc_);
  for (int k = 0; k < nc_; ++k) active[k] = c(k) <= tolerance;
  return active;
}

// Defined here, not with the model, so that models stay below the discretisation layer.
std::unique_ptr<Discretization> DcsModel::discretize(const OcpDefinition& ocp,
                                                     const DiscretizationOptions& options) const {
  return std::make_unique<PdsDiscretization>(ocp, options);
}

}  // namespace fesd
