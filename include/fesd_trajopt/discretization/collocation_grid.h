#pragma once

#include <memory>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/discretization/discretization_options.h"
#include "fesd_trajopt/discretization/trajectory.h"
#include "fesd_trajopt/discretization/trajectory_guess.h"
#include "fesd_trajopt/model/ocp_definition.h"
#include "fesd_trajopt/nlp/nlp_assembly.h"

namespace fesd {

/// The NLP variables every FESD discretisation of an OcpDefinition has, whatever the model:
/// piecewise constant controls, element lengths and collocation states. The functions below
/// build the rows that only depend on these, so each model's discretisation shares them.
struct CollocationGrid {
  std::vector<int> first_element;              ///< per control interval, and the count at the end
  std::vector<int> element_interval;           ///< per element, its control interval
  std::vector<double> nominal_steps;           ///< per element, h0 of its interval
  std::vector<int> controls;                   ///< first index, per control interval
  std::vector<int> steps;                      ///< h_n, per element (global)
  std::vector<std::vector<int>> stage_states;  ///< first index, per element, per stage
  std::vector<int> end_states;                 ///< first index of the state at each element's end

  int controlOf(int element) const { return controls[element_interval[element]]; }
  int numElements() const { return static_cast<int>(steps.size()); }
  /// Whether an element is the first of its control interval.
  bool startsInterval(int element) const {
    return first_element[element_interval[element]] == element;
  }
};

/// Throws std::invalid_argument for inconsistent sizes, horizon, grid or step options.
void validateOcp(const OcpDefinition& ocp, const DiscretizationOptions& options);
/// The elements of each control interval: interval_elements, or num_elements in each.
std::vector<int> intervalElements(const OcpDefinition& ocp, const DiscretizationOptions& options);
/// The grid's element layout (first_element, element_interval, nominal_steps: h0 = interval
/// length / its elements), before any variable is added.
CollocationGrid elementLayout(const OcpDefinition& ocp, const DiscretizationOptions& options);

/// The state (and, when the model has them, control) indices of one point, as function inputs.
std::vector<int> stateControlInputs(const CollocationGrid& grid, int state, int element, int nx,
                                    int nu);

/// Frees the control of an interval within the OCP's control bounds (guess: 0, clipped).
void freeControl(NlpAssembly& nlp, const CollocationGrid& grid, const OcpDefinition& ocp,
                 int interval);
/// Fixes the control of an interval to u.
void fixControl(NlpAssembly& nlp, const CollocationGrid& grid, int interval,
                const Eigen::VectorXd& u);
/// The controls of a guess: `controls[k]` (or 0) clipped to the current bounds.
void guessControls(const NlpAssembly& nlp, const CollocationGrid& grid, int nu,
                   const std::vector<Eigen::VectorXd>& controls, std::vector<double>& x);

/// The states of `guess` at the stage and end points of the nominal grid (every step its h0, the
/// stages at the tableau's nodes), nominal steps and the guess's controls (guessControls).
void guessGridPoints(const NlpAssembly& nlp, const CollocationGrid& grid,
                     const ButcherTableau& tableau, int nx, int nu, const TrajectoryGuess& guess,
                     std::vector<double>& x);
/// The time at `fraction` of an element of the nominal grid (every step its h0).
double nominalTime(const CollocationGrid& grid, int element, double fraction);
/// sum of the steps of each control interval = its length.
void addIntervalLengthRows(NlpAssembly& nlp, const CollocationGrid& grid, const OcpDefinition& ocp);
/// rho * sigma * ((h_n - h_{n-1}) / h0)^2 in the objective (a term vanishing with sigma) that
/// keeps relaxed NLPs away from collapsed elements; nothing when rho = 0.
void addStepRegularizer(NlpAssembly& nlp, const DiscretizationOptions& options, double h0,
                        int previous_step, int step);
/// Lagrange cost by the RK quadrature, path constraints (at element ends, or at all stages),
/// Mayer cost and terminal constraints at the last element's end.
void addCostsAndConstraints(NlpAssembly& nlp, const CollocationGrid& grid, const OcpDefinition& ocp,
                            const ButcherTableau& tableau);

/// The grid part of a solution's trajectory: control interval times and controls, element
/// times, steps, stage states and boundary states. Each element's complementarity-pair
/// matrices (num_pairs x n_s) are allocated for the model's discretisation to fill; switches
/// are left to it too.
Trajectory gridTrajectory(const double* x, const CollocationGrid& grid, const OcpDefinition& ocp,
                          int start_state, int num_pairs, double start_time);

}  // namespace fesd
