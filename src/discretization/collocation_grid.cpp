#include "fesd_trajopt/discretization/collocation_grid.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "fesd_trajopt/function/quadratic_function.h"

namespace fesd {
namespace {

constexpr double kInf = NlpAssembly::kInfinity;

void requireSize(const Eigen::VectorXd& v, int size, const char* what) {
  if (v.size() != 0 && v.size() != size) {
    throw std::invalid_argument(std::string("OcpDefinition: ") + what + " must have size " +
                                std::to_string(size) + " or be empty");
  }
}

void requireFunction(const std::shared_ptr<const SmoothFunction>& f, int inputs, bool scalar,
                     const char* what) {
  if (!f) return;
  if (f->inputSize() != inputs || (scalar && f->outputSize() != 1)) {
    throw std::invalid_argument(std::string("OcpDefinition: ") + what + " has the wrong size");
  }
}

}  // namespace

void validateOcp(const OcpDefinition& ocp, const DiscretizationOptions& options) {
  if (!ocp.model) throw std::invalid_argument("OcpDefinition: no model");
  const int nx = ocp.model->stateSize(), nu = ocp.model->controlSize();
  if (options.num_elements < 1) throw std::invalid_argument("num_elements must be >= 1");
  if (ocp.num_intervals < 1) throw std::invalid_argument("num_intervals must be >= 1");
  if (!options.interval_elements.empty()) {
    if (static_cast<int>(options.interval_elements.size()) != ocp.num_intervals) {
      throw std::invalid_argument("interval_elements must have one count per control interval");
    }
    for (int count : options.interval_elements) {
      if (count < 1) throw std::invalid_argument("interval_elements must all be >= 1");
    }
  }
  if (!(ocp.horizon > 0.0) || !std::isfinite(ocp.horizon)) {
    throw std::invalid_argument("horizon must be positive and finite");
  }
  if (!(options.step_bound >= 0.0 && options.step_bound <= 1.0)) {
    throw std::invalid_argument("step_bound (gamma_h) must be in [0, 1]");
  }
  if (!(options.pds.equilibration_big_m > 0.0)) {
    throw std::invalid_argument("pds.equilibration_big_m must be positive");
  }
  if (ocp.initial_state.size() != nx) {
    throw std::invalid_argument("OcpDefinition: initial_state must have size n_x");
  }
  requireSize(ocp.initial_state_lower, nx, "initial_state_lower");
  requireSize(ocp.initial_state_upper, nx, "initial_state_upper");
  if (ocp.initial_state_lower.size() != ocp.initial_state_upper.size()) {
    throw std::invalid_argument("OcpDefinition: give both initial state bounds or none");
  }
  requireSize(ocp.control_lower, nu, "control_lower");
  requireSize(ocp.control_upper, nu, "control_upper");
  requireSize(ocp.state_lower, nx, "state_lower");
  requireSize(ocp.state_upper, nx, "state_upper");
  requireFunction(ocp.lagrange_cost, nx + nu, true, "lagrange_cost");
  requireFunction(ocp.mayer_cost, nx, true, "mayer_cost");
  requireFunction(ocp.path_constraints, nx + nu, false, "path_constraints");
  requireFunction(ocp.terminal_constraints, nx, false, "terminal_constraints");
}

std::vector<int> intervalElements(const OcpDefinition& ocp, const DiscretizationOptions& options) {
  if (!options.interval_elements.empty()) return options.interval_elements;
  return std::vector<int>(ocp.num_intervals, options.num_elements);
}

CollocationGrid elementLayout(const OcpDefinition& ocp, const DiscretizationOptions& options) {
  CollocationGrid grid;
  const std::vector<int> counts = intervalElements(ocp, options);
  grid.first_element.push_back(0);
  for (int k = 0; k < ocp.num_intervals; ++k) {
    grid.first_element.push_back(grid.first_element.back() + counts[k]);
    grid.element_interval.insert(grid.element_interval.end(), counts[k], k);
    // T / (N m), as on a uniform grid (the same bits there).
    grid.nominal_steps.insert(grid.nominal_steps.end(), counts[k],
                              ocp.horizon / (ocp.num_intervals * counts[k]));
  }
  return grid;
}

double nominalTime(const CollocationGrid& grid, int element, double fraction) {
  const int k = grid.element_interval[element];
  const int count = grid.first_element[k + 1] - grid.first_element[k];
  // (k m + j + fraction) h0 with h0 = T / (N m): k T / N + (j + fraction) h0, the uniform grid's
  // (e + fraction) h0 to the bit.
  return (k * count + element - grid.first_element[k] + fraction) * grid.nominal_steps[element];
}

std::vector<int> stateControlInputs(const CollocationGrid& grid, int state, int element, int nx,
                                    int nu) {
  std::vector<int> inputs;
  for (int d = 0; d < nx; ++d) inputs.push_back(state + d);
  for (int d = 0; d < nu; ++d) inputs.push_back(grid.controlOf(element) + d);
  return inputs;
}

void freeControl(NlpAssembly& nlp, const CollocationGrid& grid, const OcpDefinition& ocp,
                 int interval) {
  const int first = grid.controls.at(interval);
  for (int d = 0; d < ocp.model->controlSize(); ++d) {
    const double lower = ocp.control_lower.size() ? ocp.control_lower(d) : -kInf;
    const double upper = ocp.control_upper.size() ? ocp.control_upper(d) : kInf;
    nlp.setVariableBounds(first + d, lower, upper);
    nlp.initialGuess()[first + d] = std::min(std::max(0.0, lower), upper);
  }
}

void fixControl(NlpAssembly& nlp, const CollocationGrid& grid, int interval,
                const Eigen::VectorXd& u) {
  const int first = grid.controls.at(interval);
  for (int d = 0; d < u.size(); ++d) {
    nlp.setVariableBounds(first + d, u(d), u(d));
    nlp.initialGuess()[first + d] = u(d);
  }
}

void guessControls(const NlpAssembly& nlp, const CollocationGrid& grid, int nu,
                   const std::vector<Eigen::VectorXd>& controls, std::vector<double>& x) {
  for (size_t k = 0; k < grid.controls.size(); ++k) {
    for (int d = 0; d < nu; ++d) {
      const int index = grid.controls[k] + d;
      const double wanted = k < controls.size() ? controls[k](d) : 0.0;
      x[index] = std::min(std::max(wanted, nlp.variableLower(index)), nlp.variableUpper(index));
    }
  }
}

void guessGridPoints(const NlpAssembly& nlp, const CollocationGrid& grid,
                     const ButcherTableau& tableau, int nx, int nu, const TrajectoryGuess& guess,
                     std::vector<double>& x) {
  if (!guess.state) throw std::invalid_argument("TrajectoryGuess: no state");
  auto set_state = [&](int first, double time) {
    const Eigen::VectorXd state = guess.state(time);
    if (state.size() != nx) throw std::invalid_argument("TrajectoryGuess: state of wrong size");
    std::copy(state.data(), state.data() + nx, x.begin() + first);
  };
  for (int e = 0; e < grid.numElements(); ++e) {
    for (int i = 0; i < tableau.stages; ++i) {
      set_state(grid.stage_states[e][i], nominalTime(grid, e, tableau.c(i)));
    }
    set_state(grid.end_states[e], nominalTime(grid, e, 1.0));
    x[grid.steps[e]] = grid.nominal_steps[e];
  }
  guessControls(nlp, grid, nu, guess.controls, x);
}

void addIntervalLengthRows(NlpAssembly& nlp, const CollocationGrid& grid,
                           const OcpDefinition& ocp) {
  const double interval_length = ocp.horizon / ocp.num_intervals;
  for (int k = 0; k < ocp.num_intervals; ++k) {
    const int row = nlp.addRows(1, interval_length, interval_length);
    for (int e = grid.first_element[k]; e < grid.first_element[k + 1]; ++e) {
      nlp.addLinear(row, grid.steps[e], 1.0);
    }
  }
}

void addStepRegularizer(NlpAssembly& nlp, const DiscretizationOptions& options, double h0,
                        int previous_step, int step) {
  if (options.step_regularization <= 0.0) return;
  // ((h_n - h_{n-1}) / h0)^2 = 1/2 z^T Q z on z = (h_{n-1}, h_n)
  Eigen::SparseMatrix<double> difference(2, 2);
  const double w = 2.0 / (h0 * h0);
  difference.insert(0, 0) = w;
  difference.insert(1, 1) = w;
  difference.insert(0, 1) = -w;
  difference.insert(1, 0) = -w;
  nlp.addFunctionTerm(std::make_shared<QuadraticFunction>(difference, Eigen::Vector2d::Zero(), 0.0),
                      {previous_step, step}, -1,
                      {{NlpAssembly::kObjective, options.step_regularization, true}});
}

void addCostsAndConstraints(NlpAssembly& nlp, const CollocationGrid& grid, const OcpDefinition& ocp,
                            const ButcherTableau& tableau) {
  const int nx = ocp.model->stateSize(), nu = ocp.model->controlSize();
  auto add_path_constraints = [&](int state, int element) {
    const int row = nlp.addRows(ocp.path_constraints->outputSize(), -kInf, 0.0);
    nlp.addFunctionTerm(ocp.path_constraints, stateControlInputs(grid, state, element, nx, nu), -1,
                        {{row, 1.0}});
  };
  for (int e = 0; e < grid.numElements(); ++e) {
    const std::vector<int>& stages = grid.stage_states[e];
    for (int j = 0; j < tableau.stages; ++j) {
      if (ocp.lagrange_cost) {
        nlp.addFunctionTerm(ocp.lagrange_cost, stateControlInputs(grid, stages[j], e, nx, nu),
                            grid.steps[e], {{NlpAssembly::kObjective, tableau.b(j)}});
      }
      if (ocp.path_constraints && ocp.path_constraints_at_all_stages) {
        add_path_constraints(stages[j], e);
      }
    }
    const bool end_is_stage =
        std::find(stages.begin(), stages.end(), grid.end_states[e]) != stages.end();
    if (ocp.path_constraints && !(ocp.path_constraints_at_all_stages && end_is_stage)) {
      add_path_constraints(grid.end_states[e], e);
    }
  }
  std::vector<int> end_state;
  for (int d = 0; d < nx; ++d) end_state.push_back(grid.end_states.back() + d);
  if (ocp.mayer_cost) {
    nlp.addFunctionTerm(ocp.mayer_cost, end_state, -1, {{NlpAssembly::kObjective, 1.0}});
  }
  if (ocp.terminal_constraints) {
    const int row = nlp.addRows(ocp.terminal_constraints->outputSize(), -kInf, 0.0);
    nlp.addFunctionTerm(ocp.terminal_constraints, end_state, -1, {{row, 1.0}});
  }
}

Trajectory gridTrajectory(const double* x, const CollocationGrid& grid, const OcpDefinition& ocp,
                          int start_state, int num_pairs, double start_time) {
  const int nx = ocp.model->stateSize(), nu = ocp.model->controlSize();
  Trajectory trajectory;
  const double interval_length = ocp.horizon / ocp.num_intervals;
  for (int k = 0; k <= ocp.num_intervals; ++k) {
    trajectory.interval_times.push_back(start_time + k * interval_length);
  }
  for (int k = 0; k < ocp.num_intervals; ++k) {
    trajectory.controls.push_back(Eigen::Map<const Eigen::VectorXd>(x + grid.controls[k], nu));
  }
  double time = start_time;
  trajectory.times.push_back(time);
  trajectory.states.push_back(Eigen::Map<const Eigen::VectorXd>(x + start_state, nx));
  for (int e = 0; e < grid.numElements(); ++e) {
    const int ns = static_cast<int>(grid.stage_states[e].size());
    ElementValues element{grid.element_interval[e],
                          time,
                          x[grid.steps[e]],
                          Eigen::MatrixXd(nx, ns),
                          Eigen::MatrixXd(num_pairs, ns),
                          Eigen::MatrixXd(num_pairs, ns),
                          Eigen::VectorXd()};
    for (int j = 0; j < ns; ++j) {
      element.stage_states.col(j) =
          Eigen::Map<const Eigen::VectorXd>(x + grid.stage_states[e][j], nx);
    }
    time += element.step;
    trajectory.times.push_back(time);
    trajectory.states.push_back(Eigen::Map<const Eigen::VectorXd>(x + grid.end_states[e], nx));
    trajectory.elements.push_back(std::move(element));
  }
  return trajectory;
}

}  // namespace fesd
