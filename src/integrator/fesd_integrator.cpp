#include "fesd_trajopt/integrator/fesd_integrator.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <tuple>
#include <utility>

#include "fesd_trajopt/integrator/sensitivity_chain.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {

namespace {

/// A split step: a short part at each end and the middle in halves. A switch close to a step's
/// start or end is ten times farther from the ends of its part, relative to the part's length,
/// and every part brings its own element boundaries for steps with more switches than
/// boundaries.
constexpr double kSplitFractions[] = {0.1, 0.4, 0.4, 0.1};

/// Whether a step's solution is the exact FESD solution: converged and, if anything can switch,
/// polished (complementarity exact, switches at element boundaries).
bool exact(const MpccReport& report, const RelaxedMpcc& nlp) {
  return report.converged() && (report.polished || nlp.numComplementarities() == 0);
}

/// Whether some element of a part's trajectory piece is longer than `stretch` times `nominal`.
bool stretched(const Trajectory& piece, double nominal, double stretch) {
  return std::any_of(
      piece.elements.begin(), piece.elements.end(),
      [&](const ElementValues& element) { return element.step > stretch * nominal; });
}

/// Per element of a part [start, start + length) of `elements` equal elements, the pairs with a
/// force in the reference's element at its middle.
PairModes referenceModes(const Trajectory& reference, double start, double length, int elements,
                         double tolerance) {
  PairModes modes;
  size_t e = 0;
  for (int n = 0; n < elements; ++n) {
    const double t = start + (n + 0.5) * length / elements;
    while (e + 1 < reference.elements.size() &&
           reference.elements[e].start_time + reference.elements[e].step <= t) {
      ++e;
    }
    const Eigen::MatrixXd& forces = reference.elements[e].stage_multipliers;
    std::vector<bool> active(forces.rows());
    for (int k = 0; k < forces.rows(); ++k) active[k] = forces.row(k).maxCoeff() > tolerance;
    modes.push_back(active);
  }
  return modes;
}

/// The last element of control interval k of a trajectory, as a trajectory of its own (empty
/// when it has none).
Trajectory lastElementOf(const Trajectory& trajectory, int k) {
  Trajectory last;
  for (size_t e = trajectory.elements.size(); e-- > 0;) {
    if (trajectory.elements[e].interval != k) continue;
    last.elements = {trajectory.elements[e]};
    last.states = {trajectory.states[e], trajectory.states[e + 1]};
    last.times = {trajectory.times[e], trajectory.times[e + 1]};
    last.stage_nodes = trajectory.stage_nodes;
    break;
  }
  return last;
}

/// How good a step's solution is: exact, converged, or neither.
int rank(const MpccReport& report, const RelaxedMpcc& nlp) {
  return exact(report, nlp) ? 2 : report.converged() ? 1 : 0;
}

}  // namespace

/// One simulation: the step problems of every part length that splitting reaches (built when
/// first needed), the solvers, and the result so far.
class FesdIntegrator::Run {
 public:
  Run(const FesdIntegrator& integrator, const Eigen::VectorXd& x0, double step_length,
      int num_steps)
      : options_(integrator.options_),
        state_(x0),
        nu_(integrator.model_->controlSize()),
        sensitivities_(integrator.model_->stateSize(), nu_, num_steps) {
    step_problem_.model = integrator.model_;
    step_problem_.initial_state = x0;
    step_problem_.horizon = step_length;
    step_problem_.num_intervals = 1;
    result.status = SolveStatus::kSuccess;
  }

  /// Solves user step k (of length h) under control u.
  bool step(int k, const Eigen::VectorXd& u) {
    split_ = false;
    step_ = k - first_step_;
    const bool ok = solve(0, 0, u, k * step_problem_.horizon);
    result.split_steps += split_;
    sensitivities_.endStep();
    return ok;
  }

  /// Starts afresh at x before user step k, as if the run began there: the trajectory and the
  /// sensitivities so far are dropped (the totals and the solvers stay). `arrival`: how the state
  /// was reached (its last element's multipliers predict the active set), under `control`; empty
  /// when unknown.
  void restart(const Eigen::VectorXd& x, int k, Trajectory arrival,
               const Eigen::VectorXd& control) {
    state_ = x;
    first_step_ = k;
    previous_control_ = control;
    result.trajectory = Trajectory();
    arrival_ = std::move(arrival);
    sensitivities_ = SensitivityChain(static_cast<int>(x.size()), nu_, 1);
  }

  /// The sensitivities of the whole run, with those of its switch times.
  SimulationSensitivities sensitivities() const {
    return sensitivities_.finish(result.trajectory.switches);
  }

  const std::string& failure() const { return failure_; }
  const Discretization& discretization() { return *partOf(0, 0, kSwitchDetection).discretization; }
  double wallSeconds() const { return stopwatch_.wallSeconds(); }
  double cpuSeconds() const { return stopwatch_.cpuSeconds(); }

  SimulationResult result;

 private:
  /// How a part is discretised: with switch detection (FESD, if the options have it), the same
  /// with twice the elements, or with fixed steps.
  enum Kind { kSwitchDetection, kRefined, kFixedSteps };
  struct Part {
    double length;
    int num_elements;
    std::unique_ptr<Discretization> discretization;
    std::vector<double> previous_solution;
  };
  /// One solve of a part: its report, the trajectory piece, whether the retry path gave it.
  struct Attempt {
    MpccReport report;
    Trajectory piece;
    bool retried = false;
    ActiveSetOutcome path = ActiveSetOutcome::kFailed;  ///< kFailed: the homotopy solved it
    Discretization* discretization = nullptr;           ///< whose solution it is
    PairModes modes;           ///< the modes its solution takes (SimulationOptions::sensitivities)
    bool fixed_steps = false;  ///< integrated with fixed steps where FESD found no solution
  };

  /// Solves [start_time, start_time + length) under control u from the current state, where
  /// length = h 0.1^tenths 0.4^middles. A part whose solution is not exact is split
  /// (kSplitFractions) while SimulationOptions::max_step_splits allows; a part of a split step
  /// that cannot be split any further and does not converge is integrated with fixed steps.
  /// False when it stops the simulation.
  bool solve(int tenths, int middles, const Eigen::VectorXd& u, double start_time) {
    Part& part = partOf(tenths, middles, kSwitchDetection);
    const bool can_split = tenths + middles < options_.max_step_splits;
    const bool split_first = options_.split_before_homotopy && can_split;
    Attempt attempt = solvePart(part, u, start_time, !split_first);
    refineIfNeeded(part, tenths, middles, u, start_time, !can_split, attempt);
    const bool timed_out = attempt.report.status == SolveStatus::kTimeout;
    if (can_split && !timed_out && !exact(attempt.report, part.discretization->nlp())) {
      result.totals.addEffort(attempt.report);  // the attempts on the whole part count too
      split_ = true;
      double time = start_time;
      for (const double fraction : kSplitFractions) {
        const bool end_part = fraction == kSplitFractions[0];
        if (!solve(tenths + end_part, middles + !end_part, u, time)) return false;
        time += fraction * part.length;
      }
      return true;
    }
    if (!can_split && tenths + middles > 0 && !timed_out && !attempt.report.converged()) {
      // A tiny part (1e-4 h after four levels) that still holds more switches than FESD can
      // place, e.g. a contact and a release 2e-6 apart: fixed steps keep the simulation going
      // at an error of the order of the part's length, and its switches are flagged unresolved.
      Attempt fixed = solvePart(partOf(tenths, middles, kFixedSteps), u, start_time);
      fixed.report.addEffort(attempt.report);
      if (fixed.report.converged()) {
        attempt = std::move(fixed);
        attempt.fixed_steps = true;
        ++result.fixed_step_parts;
      }
    }
    result.retried_steps += attempt.retried;
    result.predicted_parts += attempt.path == ActiveSetOutcome::kPredicted;
    result.located_parts += attempt.path == ActiveSetOutcome::kLocated;
    result.homotopy_parts += attempt.path == ActiveSetOutcome::kFailed;
    result.totals.accumulate(attempt.report);
    result.step_histories.push_back(attempt.report.history);
    if (options_.sensitivities) addSensitivity(attempt);
    result.trajectory.append(attempt.piece);
    state_ = attempt.piece.finalState();
    previous_control_ = u;
    if (attempt.report.converged()) return true;
    result.status = attempt.report.status;
    failure_ = attempt.report.message;
    return false;
  }

  /// SimulationOptions::refine_elements: the part on twice the elements replaces a solution that
  /// is exact but stretched, or not exact where `last_resort` (the part cannot be split), if its
  /// own solution is exact and not stretched.
  void refineIfNeeded(const Part& part, int tenths, int middles, const Eigen::VectorXd& u,
                      double start_time, bool last_resort, Attempt& attempt) {
    const bool is_exact = exact(attempt.report, part.discretization->nlp());
    const double nominal = part.length / part.num_elements;
    const bool needed =
        is_exact ? stretched(attempt.piece, nominal, options_.max_element_stretch) : last_resort;
    if (!options_.refine_elements || attempt.report.status == SolveStatus::kTimeout || !needed) {
      return;
    }
    Part& refined_part = partOf(tenths, middles, kRefined);
    Attempt refined =
        solvePart(refined_part, u, start_time, !is_exact || options_.refine_by_homotopy);
    // Kept only within the stretch bound of the coarser elements: a refined part whose switches
    // took several boundaries can leave an element longer than that.
    if (exact(refined.report, refined_part.discretization->nlp()) &&
        !stretched(refined.piece, nominal, options_.max_element_stretch)) {
      refined.report.addEffort(attempt.report);
      refined.retried = refined.retried || attempt.retried;
      attempt = std::move(refined);
      ++result.refined_parts;
    } else {
      attempt.report.addEffort(refined.report);
    }
  }

  /// The sensitivities of an accepted part, chained to the run's.
  void addSensitivity(const Attempt& attempt) {
    StepSensitivity part;
    if (sensitivities_.defined()) part = partSensitivity(attempt);
    sensitivities_.addPart(part, step_, static_cast<int>(attempt.piece.elements.size()));
  }

  /// The sensitivities of a part by its own start state and control. Time-stepping (switch
  /// detection off) places switches at stage points, so only FESD's parts are checked for pairs
  /// that touch without switching and for switches at their end.
  StepSensitivity partSensitivity(const Attempt& attempt) {
    StepSensitivity part;
    const double tolerance = options_.activity_tolerance;
    if (!attempt.report.converged()) {
      part.why_undefined = "its solve did not converge";
    } else if (attempt.fixed_steps) {
      part.why_undefined = "integrated with fixed steps where FESD found no solution";
    } else if (attempt.discretization->stepsAreFree()) {
      const Trajectory* before = arrivedFrom();
      const std::vector<bool> active_before =
          before == nullptr ? std::vector<bool>{} : activeAtEnd(*before, tolerance);
      part.why_undefined = degeneracy(*attempt.discretization, attempt.piece, attempt.modes,
                                      active_before, tolerance);
      if (part.why_undefined.empty()) {
        part.why_undefined =
            switchAtEnd(*attempt.discretization, attempt.piece, attempt.modes, tolerance);
      }
    }
    if (!part.why_undefined.empty()) return part;
    return stepSensitivity(*attempt.discretization, attempt.report.solution, attempt.modes,
                           static_cast<int>(state_.size()),
                           options_.homotopy.complementarity_tolerance, sensitivity_newton_);
  }

  /// One part from the current state: its active sets, then (`homotopy_fallback`, or without
  /// active-set steps) the homotopy and its retry path if that is not exact.
  Attempt solvePart(Part& part, const Eigen::VectorXd& u, double start_time,
                    bool homotopy_fallback = true) {
    Discretization& discretization = *part.discretization;
    discretization.setInitialState(state_);
    const Trajectory* before = arrivedFrom();
    if (before != nullptr) {
      discretization.continueFrom(*before,
                                  previous_control_.size() == u.size() && previous_control_ == u);
    }
    if (u.size() > 0) discretization.fixControl(0, u);
    const std::vector<double> guess =
        part.previous_solution.empty() || !options_.reuse_previous_step
            ? discretization.constantGuess({u})
            : discretization.translatedGuess(part.previous_solution);
    const RelaxedMpcc& nlp = discretization.nlp();
    Attempt attempt;
    attempt.discretization = &discretization;
    // Out of time, the homotopy reports the timeout (with its interrupted iterate).
    if (options_.active_set_steps && remainingBudget() != 0.0 &&
        (discretization.stepsAreFree() || nlp.numComplementarities() == 0)) {
      const bool first = before == nullptr;
      const PairModes from_start =
          predictModes(before,
                       first ? discretization.activeAt(state_, options_.activity_tolerance)
                             : std::vector<bool>{},
                       part.num_elements, options_.homotopy.complementarity_tolerance);
      const PairModes predicted =
          reference_ != nullptr ? referenceModes(*reference_, start_time, part.length,
                                                 part.num_elements, options_.activity_tolerance)
                                : from_start;
      ActiveSetOptions fast_options;
      fast_options.tolerance = options_.homotopy.complementarity_tolerance;
      fast_options.start_time = start_time;
      fast_options.activity_tolerance = options_.activity_tolerance;
      fast_options.penetration_tolerance = options_.penetration_tolerance;
      ActiveSetStep fast =
          solveByActiveSets(discretization, guess, predicted, fast_options, newton_);
      result.newton_iterations += fast.newton_iterations;
      if (fast.outcome == ActiveSetOutcome::kFailed && predicted != from_start) {
        fast = solveByActiveSets(discretization, guess, from_start, fast_options, newton_);
        result.newton_iterations += fast.newton_iterations;
      }
      if (fast.outcome != ActiveSetOutcome::kFailed) {
        attempt.report = std::move(fast.report);
        attempt.piece = std::move(fast.piece);
        attempt.path = fast.outcome;
        attempt.modes = std::move(fast.modes);
        part.previous_solution = attempt.report.solution;
        return attempt;
      }
    }
    if (!homotopy_fallback && options_.active_set_steps) {
      attempt.report.status = SolveStatus::kComplementarityNotMet;
      attempt.report.message = "no active set found";
      return attempt;
    }
    attempt.report = homotopy(solver_, options_.homotopy)
                         .solve(discretization.nlp(), guess, -1.0, remainingBudget());
    if (!exact(attempt.report, nlp) && attempt.report.status != SolveStatus::kTimeout) {
      MpccReport retry = homotopy(retry_solver_, options_.retry_homotopy)
                             .solve(discretization.nlp(), guess, -1.0, remainingBudget());
      attempt.retried = rank(retry, nlp) > rank(attempt.report, nlp);
      if (attempt.retried) {
        retry.addEffort(attempt.report);  // both attempts' effort counts
        attempt.report = std::move(retry);
      } else {
        attempt.report.addEffort(retry);
      }
    }
    part.previous_solution = attempt.report.solution;
    attempt.piece =
        discretization.extract(attempt.report.solution.data(), start_time,
                               options_.activity_tolerance, options_.penetration_tolerance);
    if (options_.sensitivities) {
      attempt.modes =
          modesOf(attempt.piece, discretization.activeAt(state_, options_.activity_tolerance),
                  options_.activity_tolerance);
    }
    return attempt;
  }

  /// What the current state was reached by: the trajectory so far, else the arrival given to
  /// restart; nullptr at a start with no history.
  const Trajectory* arrivedFrom() const {
    if (!result.trajectory.elements.empty()) return &result.trajectory;
    return arrival_.elements.empty() ? nullptr : &arrival_;
  }

  /// A homotopy solver, built when first needed: building one (an Ipopt application) costs
  /// ~0.15 ms, more than a whole step solved by its active set.
  static MpccSolver& homotopy(std::unique_ptr<MpccSolver>& solver, const HomotopyOptions& options) {
    if (!solver) solver = std::make_unique<MpccSolver>(options);
    return *solver;
  }

  /// The part of that length and kind, built when first needed.
  Part& partOf(int tenths, int middles, Kind kind) {
    const auto key = std::make_tuple(tenths, middles, kind);
    const auto found = parts_.find(key);
    if (found != parts_.end()) return found->second;
    OcpDefinition problem = step_problem_;
    problem.horizon *= std::pow(0.1, tenths) * std::pow(0.4, middles);
    DiscretizationOptions discretization = options_.discretization;
    discretization.switch_detection = discretization.switch_detection && kind != kFixedSteps;
    if (kind == kRefined) discretization.num_elements *= 2;
    discretization.interval_elements.clear();  // a step is one interval
    discretization.gap_guards.clear();
    Part part{
        problem.horizon, discretization.num_elements, discretize(problem, discretization), {}};
    return parts_.emplace(key, std::move(part)).first->second;
  }

  /// What is left of the wall-time budget; negative (none) without a budget.
  double remainingBudget() const {
    return std::isfinite(options_.wall_time_budget)
               ? std::max(0.0, options_.wall_time_budget - stopwatch_.wallSeconds())
               : -1.0;
  }

  const SimulationOptions& options_;
  Stopwatch stopwatch_;
  OcpDefinition step_problem_;
  std::unique_ptr<MpccSolver> solver_, retry_solver_;  ///< the homotopy and its retry path
  /// Newton on the active sets; it keeps the factorisation's structure from step to step.
  SquareNewton newton_;
  /// The sensitivities' own: the stepping's factorisations (and so its path) stay as without.
  SquareNewton sensitivity_newton_;
  Eigen::VectorXd state_;
  int nu_;
  Eigen::VectorXd previous_control_;  ///< of the last part in the trajectory (or the arrival)
  Trajectory arrival_;                ///< restart's: how a restarted run's state was reached
  /// A trajectory close to the one sought (a plan being verified): its forces predict each
  /// part's active sets; where its modes fail, those the run's own history predicts are tried
  /// too (a run drifts from it: one run from its start, and within an interval also one started
  /// from its states, on a finer grid); nullptr: predicted from the start.
  const Trajectory* reference_ = nullptr;

 public:
  void setReference(const Trajectory* reference) { reference_ = reference; }
  /// By (tenths, middles, kind); a map's references stay valid as parts are added.
  std::map<std::tuple<int, int, Kind>, Part> parts_;
  bool split_ = false;  ///< the current step was split
  int step_ = 0;        ///< the step being solved, counted from the run's (re)start
  int first_step_ = 0;  ///< the user step the run (re)started at
  std::string failure_;
  SensitivityChain sensitivities_;
};

FesdIntegrator::FesdIntegrator(std::shared_ptr<const DynamicsModel> model,
                               SimulationOptions options)
    : model_(std::move(model)), options_(std::move(options)) {
  if (!model_) throw std::invalid_argument("FesdIntegrator: no model");
}

SimulationResult FesdIntegrator::simulate(const Eigen::VectorXd& x0, double horizon, int num_steps,
                                          const std::vector<Eigen::VectorXd>& controls,
                                          const Trajectory* reference) {
  if (num_steps < 1) throw std::invalid_argument("FesdIntegrator: num_steps must be >= 1");
  const int nu = model_->controlSize();
  if (!(controls.size() == static_cast<size_t>(num_steps) || controls.size() == 1 ||
        (controls.empty() && nu == 0))) {
    throw std::invalid_argument("FesdIntegrator: give one control per step or a single one");
  }
  Run run(*this, x0, horizon / num_steps, num_steps);
  run.setReference(reference);
  SimulationResult& result = run.result;
  for (int step = 0; step < num_steps; ++step) {
    const Eigen::VectorXd u =
        controls.empty() ? Eigen::VectorXd() : controls[controls.size() == 1 ? 0 : step];
    if (!run.step(step, u)) {
      result.message = "step " + std::to_string(step) + " of " + std::to_string(num_steps) +
                       " did not converge: " + run.failure();
      break;
    }
    ++result.completed_steps;
  }
  classifySwitches(result.trajectory,
                   run.discretization().activeAt(x0, options_.activity_tolerance),
                   options_.activity_tolerance, options_.penetration_tolerance);
  if (result.status == SolveStatus::kSuccess) {
    std::ostringstream message;
    message << "simulated " << num_steps << " step(s): " << result.totals.iterations
            << " Ipopt iterations, " << result.trajectory.switches.size() << " switch(es)";
    if (options_.active_set_steps) {
      message << "; parts by active set " << result.predicted_parts << " predicted, "
              << result.located_parts << " with switches located, " << result.homotopy_parts
              << " by homotopy (" << result.newton_iterations << " Newton iterations)";
    }
    if (result.retried_steps > 0) message << ", " << result.retried_steps << " step(s) retried";
    if (result.split_steps > 0) message << ", " << result.split_steps << " step(s) split";
    if (result.refined_parts > 0) {
      message << ", " << result.refined_parts << " part(s) refined";
    }
    result.message = message.str();
  }
  if (!result.trajectory.switchesResolved()) {
    result.message += "; " + describeUnresolvedSwitches(result.trajectory.unresolved_switches);
  }
  if (options_.sensitivities) result.sensitivities = run.sensitivities();
  result.totals.status = result.status;
  result.totals.message = result.message;
  result.totals.wall_seconds = run.wallSeconds();
  result.totals.cpu_seconds = run.cpuSeconds();
  return std::move(result);  // run.result: no copy of the trajectory and sensitivities
}

ShootingResult FesdIntegrator::shoot(const std::vector<Eigen::VectorXd>& starts, double step_length,
                                     const std::vector<Eigen::VectorXd>& controls,
                                     const Trajectory* reference) {
  const int steps = static_cast<int>(starts.size());
  if (steps < 1) throw std::invalid_argument("FesdIntegrator::shoot: no start state");
  if (!(controls.size() == starts.size() || (controls.empty() && model_->controlSize() == 0))) {
    throw std::invalid_argument("FesdIntegrator::shoot: give one control per start state");
  }
  ShootingResult shooting;
  shooting.status = SolveStatus::kSuccess;
  Run run(*this, starts[0], step_length, 1);
  run.setReference(reference);
  for (int k = 0; k < steps; ++k) {
    Trajectory arrival =
        k > 0 && reference != nullptr ? lastElementOf(*reference, k - 1) : Trajectory();
    const bool arrived = !arrival.elements.empty() && !controls.empty();
    run.restart(starts[k], k, std::move(arrival), arrived ? controls[k - 1] : Eigen::VectorXd());
    const bool ok = run.step(k, controls.empty() ? Eigen::VectorXd() : controls[k]);
    Trajectory piece = std::move(run.result.trajectory);
    classifySwitches(piece, run.discretization().activeAt(starts[k], options_.activity_tolerance),
                     options_.activity_tolerance, options_.penetration_tolerance);
    shooting.steps.push_back(std::move(piece));
    if (options_.sensitivities) {
      const SimulationSensitivities derivatives = run.sensitivities();
      shooting.why_undefined.push_back(derivatives.why_undefined);
      shooting.transitions.push_back(
          derivatives.defined_steps == 1
              ? Eigen::MatrixXd(derivatives.states[0].leftCols(starts[k].size()))
              : Eigen::MatrixXd());
    }
    if (!ok) {
      shooting.status = run.result.status;
      shooting.message = "step " + std::to_string(k) + " of " + std::to_string(steps) +
                         " did not converge: " + run.failure();
      break;
    }
  }
  shooting.totals = run.result.totals;
  shooting.totals.status = shooting.status;
  shooting.totals.wall_seconds = run.wallSeconds();
  shooting.totals.cpu_seconds = run.cpuSeconds();
  return shooting;
}

}  // namespace fesd
