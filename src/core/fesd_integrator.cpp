#include "fesd_trajopt/core/fesd_integrator.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <utility>

#include "fesd_trajopt/core/stopwatch.h"

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

/// How good a step's solution is: exact, converged, or neither.
int rank(const MpccReport& report, const RelaxedMpcc& nlp) {
  return exact(report, nlp) ? 2 : report.converged() ? 1 : 0;
}

}  // namespace

/// One simulation: the step problems of every part length that splitting reaches (built when
/// first needed), the solvers, and the result so far.
class FesdIntegrator::Run {
 public:
  Run(const FesdIntegrator& integrator, const Eigen::VectorXd& x0, double step_length)
      : options_(integrator.options_),
        solver_(options_.homotopy),
        retry_solver_(options_.retry_homotopy),
        state_(x0) {
    step_problem_.model = integrator.model_;
    step_problem_.initial_state = x0;
    step_problem_.horizon = step_length;
    step_problem_.num_intervals = 1;
    result.status = SolveStatus::kSuccess;
  }

  /// Solves user step k (of length h) under control u.
  bool step(int k, const Eigen::VectorXd& u) {
    split_ = false;
    const bool ok = solve(0, 0, u, k * step_problem_.horizon);
    result.split_steps += split_;
    return ok;
  }

  const std::string& failure() const { return failure_; }
  const Discretization& discretization() { return *partOf(0, 0).discretization; }
  double wallSeconds() const { return stopwatch_.wallSeconds(); }
  double cpuSeconds() const { return stopwatch_.cpuSeconds(); }

  SimulationResult result;

 private:
  struct Part {
    double length;
    std::unique_ptr<Discretization> discretization;
    std::vector<double> previous_solution;
  };

  /// Solves [start_time, start_time + length) under control u from the current state, where
  /// length = h 0.1^tenths 0.4^middles; a part whose solution is not exact is split
  /// (kSplitFractions) while SimulationOptions::max_step_splits allows. False when it stops
  /// the simulation.
  bool solve(int tenths, int middles, const Eigen::VectorXd& u, double start_time) {
    Part& part = partOf(tenths, middles);
    Discretization& discretization = *part.discretization;
    discretization.setInitialState(state_);
    if (!result.trajectory.elements.empty()) {
      discretization.continueFrom(result.trajectory,
                                  previous_control_.size() == u.size() && previous_control_ == u);
    }
    previous_control_ = u;
    if (u.size() > 0) discretization.fixControl(0, u);
    const std::vector<double> guess =
        part.previous_solution.empty() || !options_.reuse_previous_step
            ? discretization.constantGuess({u})
            : discretization.translatedGuess(part.previous_solution);
    const RelaxedMpcc& nlp = discretization.nlp();
    MpccReport report = solver_.solve(discretization.nlp(), guess, -1.0, remainingBudget());
    bool retried = false;
    if (!exact(report, nlp) && report.status != SolveStatus::kTimeout) {
      MpccReport retry = retry_solver_.solve(discretization.nlp(), guess, -1.0, remainingBudget());
      retried = rank(retry, nlp) > rank(report, nlp);
      if (retried) {
        retry.addEffort(report);  // both attempts' effort counts
        report = std::move(retry);
      } else {
        report.addEffort(retry);
      }
    }
    if (!exact(report, nlp) && report.status != SolveStatus::kTimeout &&
        tenths + middles < options_.max_step_splits) {
      result.totals.addEffort(report);  // the attempts on the whole part count too
      split_ = true;
      double time = start_time;
      for (const double fraction : kSplitFractions) {
        const bool end_part = fraction == kSplitFractions[0];
        if (!solve(tenths + end_part, middles + !end_part, u, time)) return false;
        time += fraction * part.length;
      }
      return true;
    }
    result.retried_steps += retried;
    part.previous_solution = report.solution;
    result.totals.accumulate(report);
    result.step_histories.push_back(report.history);
    Trajectory piece =
        discretization.extract(report.solution.data(), start_time, options_.activity_tolerance,
                               options_.penetration_tolerance);
    result.trajectory.append(piece);
    state_ = piece.finalState();
    if (report.converged()) return true;
    result.status = report.status;
    failure_ = report.message;
    return false;
  }

  Part& partOf(int tenths, int middles) {
    const auto found = parts_.find({tenths, middles});
    if (found != parts_.end()) return found->second;
    OcpDefinition problem = step_problem_;
    problem.horizon *= std::pow(0.1, tenths) * std::pow(0.4, middles);
    Part part{problem.horizon, discretize(problem, options_.discretization), {}};
    return parts_.emplace(std::make_pair(tenths, middles), std::move(part)).first->second;
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
  MpccSolver solver_, retry_solver_;
  Eigen::VectorXd state_;
  Eigen::VectorXd previous_control_;           ///< of the part solved last
  std::map<std::pair<int, int>, Part> parts_;  ///< by (tenths, middles); references stay valid
  bool split_ = false;                         ///< the current step was split
  std::string failure_;
};

FesdIntegrator::FesdIntegrator(std::shared_ptr<const DynamicsModel> model,
                               SimulationOptions options)
    : model_(std::move(model)), options_(std::move(options)) {
  if (!model_) throw std::invalid_argument("FesdIntegrator: no model");
}

SimulationResult FesdIntegrator::simulate(const Eigen::VectorXd& x0, double horizon, int num_steps,
                                          const std::vector<Eigen::VectorXd>& controls) {
  if (num_steps < 1) throw std::invalid_argument("FesdIntegrator: num_steps must be >= 1");
  const int nu = model_->controlSize();
  if (!(controls.size() == static_cast<size_t>(num_steps) || controls.size() == 1 ||
        (controls.empty() && nu == 0))) {
    throw std::invalid_argument("FesdIntegrator: give one control per step or a single one");
  }
  Run run(*this, x0, horizon / num_steps);
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
    if (result.retried_steps > 0) message << ", " << result.retried_steps << " step(s) retried";
    if (result.split_steps > 0) message << ", " << result.split_steps << " step(s) split";
    result.message = message.str();
  }
  if (!result.trajectory.switchesResolved()) {
    result.message += "; " + describeUnresolvedSwitches(result.trajectory.unresolved_switches);
  }
  result.totals.status = result.status;
  result.totals.message = result.message;
  result.totals.wall_seconds = run.wallSeconds();
  result.totals.cpu_seconds = run.cpuSeconds();
  return result;
}

}  // namespace fesd
