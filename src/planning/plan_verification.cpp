// The verification of a plan: interval by interval (the discretisation's error) and open loop
// (the execution's drift), with the open-loop gain and the contacts the plan does not hold.
#include "fesd_trajopt/planning/plan_verification.h"

#include <algorithm>
#include <cmath>
#include <functional>
#include <future>
#include <sstream>

#include "fesd_trajopt/scene/moving_part.h"
#include "fesd_trajopt/scene/pair_check.h"
#include "fesd_trajopt/solver/stopwatch.h"

namespace fesd {
namespace {

/// Whether a force of row `row` exceeds the activity tolerance somewhere in an element.
bool pushes(const ElementValues& element, int row) {
  return element.stage_multipliers.rows() > row &&
         element.stage_multipliers.row(row).maxCoeff() > kDefaultActivityTolerance;
}

/// Per control interval, whether the trajectory holds a force of row `row` in it.
std::vector<bool> heldIntervals(const Trajectory& trajectory, int row) {
  std::vector<bool> held(trajectory.controls.size(), false);
  for (const ElementValues& element : trajectory.elements) {
    if (pushes(element, row)) held[element.interval] = true;
  }
  return held;
}

/// The smallest gap of `pair` along an element's collocation polynomial and where: located on
/// the pair's constraint row `row` of `constraints` (closestApproach), measured by the scene.
Graze closestInElement(const Scene& scene, const SmoothFunction& constraints, int row,
                       const ContactPair& pair, const Trajectory& trajectory, int e) {
  const ElementValues& element = trajectory.elements[e];
  const ClosestApproach closest = closestApproach(constraints, row, trajectory.stage_nodes,
                                                  trajectory.states[e], element.stage_states);
  Graze graze;
  graze.pair = pair;
  graze.interval = element.interval;
  graze.element = e;
  graze.fraction = closest.fraction;
  graze.time = element.start_time + closest.fraction * element.step;
  graze.depth = scene.pairGap(pair, collocationState(trajectory.stage_nodes, trajectory.states[e],
                                                     element.stage_states, closest.fraction));
  return graze;
}

/// The smallest gap of `pair` (row `row` of `constraints`) along the trajectory's polynomials in
/// control interval k, found among the elements whose sampled lowest value (lowest_constraints,
/// c / |grad c|) comes within `near` of the boundary; depth infinity when none does.
Graze closestInInterval(const Scene& scene, const SmoothFunction& constraints, int row,
                        const ContactPair& pair, const Trajectory& trajectory, int k, double near) {
  Graze best;
  best.pair = pair;
  best.interval = k;
  best.depth = std::numeric_limits<double>::infinity();
  for (int e = 0; e < static_cast<int>(trajectory.elements.size()); ++e) {
    const ElementValues& element = trajectory.elements[e];
    if (element.interval != k) continue;
    if (element.lowest_constraints.size() > row && element.lowest_constraints(row) > near) continue;
    const Graze graze = closestInElement(scene, constraints, row, pair, trajectory, e);
    if (graze.depth < best.depth) best = graze;
  }
  return best;
}

/// The modelled pairs of decisions, in order (the rows of a plan's multipliers).
std::vector<ContactPair> modelledOf(const std::vector<PairDecision>& decisions) {
  std::vector<ContactPair> pairs;
  for (const PairDecision& decision : decisions) {
    if (decision.modelled) pairs.push_back(decision.pair);
  }
  return pairs;
}

/// Makes every checked pair that comes within the margin along `paths` modelled; true if one did.
bool modelPairsThatCameNear(const Scene& scene,
                            const std::vector<std::vector<Eigen::VectorXd>>& paths, double margin,
                            std::vector<PairDecision>& decisions) {
  std::vector<ContactPair> checked;
  for (const PairDecision& decision : decisions) {
    if (decision.checked) checked.push_back(decision.pair);
  }
  if (checked.empty()) return false;
  std::vector<double> gaps(checked.size(), std::numeric_limits<double>::infinity());
  for (const std::vector<Eigen::VectorXd>& path : paths) {
    const std::vector<double> along = smallestGaps(scene, checked, path);
    for (size_t k = 0; k < gaps.size(); ++k) gaps[k] = std::min(gaps[k], along[k]);
  }
  bool grew = false;
  size_t k = 0;
  for (PairDecision& decision : decisions) {
    if (!decision.checked) continue;
    if (withinMargin(scene, decision.pair, gaps[k++], margin)) {
      decision.modelled = true;
      decision.checked = false;
      grew = true;
    }
  }
  return grew;
}

/// The largest singular value of a small matrix by power iteration on A^T A (deterministic; a
/// gain is reported to a few digits).
double spectralNorm(const Eigen::MatrixXd& a) {
  const Eigen::MatrixXd s = a.transpose() * a;
  Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(s.cols(), 1.0, 2.0).normalized();
  double eigenvalue = 0.0;
  for (int iteration = 0; iteration < 500; ++iteration) {
    const Eigen::VectorXd w = s * v;
    const double next = v.dot(w);
    if (w.norm() == 0.0) return 0.0;
    v = w.normalized();
    if (std::fabs(next - eigenvalue) <= 1e-12 * next) {
      eigenvalue = next;
      break;
    }
    eigenvalue = next;
  }
  return std::sqrt(std::max(eigenvalue, 0.0));
}

/// The largest spectral norm of the products transitions[n-1] ... transitions[k] over k, from
/// the end back to the first undefined transition.
double largestGain(const std::vector<Eigen::MatrixXd>& transitions,
                   const std::vector<std::string>& why_undefined, std::string& note) {
  double gain = std::numeric_limits<double>::quiet_NaN();
  Eigen::MatrixXd product;
  for (int k = static_cast<int>(transitions.size()) - 1; k >= 0; --k) {
    if (transitions[k].size() == 0 || !transitions[k].allFinite()) {
      note = "the open-loop gain leaves out intervals 0 to " + std::to_string(k) + " (interval " +
             std::to_string(k) + ": sensitivities undefined: " + why_undefined[k] + ")";
      break;
    }
    product = product.size() == 0 ? transitions[k] : Eigen::MatrixXd(product * transitions[k]);
    const double norm = spectralNorm(product);
    gain = std::isnan(gain) ? norm : std::max(gain, norm);
  }
  return gain;
}

/// An open-loop re-simulation of a plan's controls from its start.
struct OpenLoop {
  Trajectory trajectory;           ///< of the full scene; empty when it failed
  std::vector<ContactPair> pairs;  ///< of its multipliers' rows
  double error = std::numeric_limits<double>::infinity();
};

/// The plan's controls re-simulated from its start in one run (the fine grid `fine()` gives,
/// within what is left of the budget), lazily: the drift may bring the bodies near pairs the plan
/// never met, which are then modelled and the run repeated. The plan (its forces those of
/// `plan_pairs`) predicts the run's active sets.
OpenLoop openLoop(const SceneTask& task, const Trajectory& plan,
                  const std::vector<ContactPair>& plan_pairs, std::vector<PairDecision> decisions,
                  const std::function<SimulationOptions()>& fine, double margin) {
  OpenLoop open;
  const int intervals = static_cast<int>(plan.controls.size());
  for (bool grew = true; grew;) {
    const MovingPart part = movingPart(task, decisions);
    const Trajectory reference = partTrajectory(task, part, plan, plan_pairs);
    const SimulationResult result =
        FesdIntegrator(part.task.scene.model(part.modelled), fine())
            .simulate(partState(task, part, plan.states.front()), task.horizon, intervals,
                      plan.controls, &reference);
    if (result.status != SolveStatus::kSuccess) break;
    open.trajectory = fullSceneTrajectory(task, part, result.trajectory);
    open.pairs = part.modelled_in_task;
    grew = modelPairsThatCameNear(task.scene, {densePath(open.trajectory)}, margin, decisions);
    if (!grew) open.error = (open.trajectory.finalState() - plan.finalState()).norm();
  }
  return open;
}

}  // namespace

std::vector<Eigen::VectorXd> intervalBoundaryStates(const Trajectory& trajectory) {
  std::vector<Eigen::VectorXd> states;
  int next = 0;
  for (size_t e = 0; e < trajectory.elements.size(); ++e) {
    if (trajectory.elements[e].interval == next) {
      states.push_back(trajectory.states[e]);
      ++next;
    }
  }
  states.push_back(trajectory.finalState());
  return states;
}

std::vector<Graze> planGrazes(const SceneTask& task, const Trajectory& plan,
                              const std::vector<ContactPair>& modelled, double depth) {
  std::vector<Graze> grazes;
  if (modelled.empty() || plan.elements.empty()) return grazes;
  const std::shared_ptr<const DcsModel> model = task.scene.model(modelled);
  for (int row = 0; row < static_cast<int>(modelled.size()); ++row) {
    const std::vector<bool> held = heldIntervals(plan, row);
    const double size = task.scene.pairSize(modelled[row]);
    for (int k = 0; k < static_cast<int>(held.size()); ++k) {
      if (held[k]) continue;
      // c / |grad c| is the gap to first order; a tenth of the pair's size spares the search in
      // elements that pass far away.
      const Graze graze = closestInInterval(task.scene, *model->constraints(), row, modelled[row],
                                            plan, k, 0.1 * size);
      if (graze.depth < -depth * size) grazes.push_back(graze);
    }
  }
  std::sort(grazes.begin(), grazes.end(),
            [](const Graze& a, const Graze& b) { return a.time < b.time; });
  return grazes;
}

std::string describeGrazes(const Scene& scene, const std::vector<Graze>& grazes) {
  if (grazes.empty()) return "";
  std::ostringstream text;
  text.precision(3);
  text << grazes.size() << " contact(s) the plan does not hold: ";
  for (size_t i = 0; i < grazes.size() && i < 3; ++i) {
    const Graze& g = grazes[i];
    text << (i ? "; " : "") << scene.pairName(g.pair) << " at t = " << g.time << " ("
         << (g.touched ? "touched in the re-simulation, " : "") << "the plan's gap "
         << scene.userLength(g.depth) << ")";
  }
  if (grazes.size() > 3) text << "; ...";
  return text.str();
}

Verification verifyPlan(const SceneTask& task, const Trajectory& plan,
                        const std::vector<PairDecision>& decisions, const SimulationOptions& fine,
                        double margin, double graze_depth) {
  Stopwatch stopwatch;
  Verification verification;
  const std::vector<ContactPair> plan_pairs = modelledOf(decisions);
  const std::vector<Eigen::VectorXd> boundaries = intervalBoundaryStates(plan);
  const int intervals = static_cast<int>(plan.controls.size());
  const double step = task.horizon / intervals;
  const auto remaining = [&] {
    SimulationOptions options = fine;
    options.wall_time_budget = std::max(0.0, fine.wall_time_budget - stopwatch.wallSeconds());
    return options;
  };
  // The open-loop run in a thread of its own while the intervals are re-simulated: neither
  // depends on the other (each its own integrator), so the answer is the same either way.
  std::future<OpenLoop> open_loop = std::async(std::launch::async, [&] {
    return openLoop(task, plan, plan_pairs, decisions, remaining, margin);
  });
  std::vector<PairDecision> in_use = decisions;
  // Multiple shooting, lazily: every checked pair that an interval's re-simulation brings near.
  ShootingResult shooting;
  MovingPart part;
  std::vector<Trajectory> pieces;
  for (bool grew = true; grew;) {
    part = movingPart(task, in_use);
    SimulationOptions options = remaining();
    options.sensitivities = true;
    FesdIntegrator integrator(part.task.scene.model(part.modelled), options);
    std::vector<Eigen::VectorXd> starts;
    for (int k = 0; k < intervals; ++k) starts.push_back(partState(task, part, boundaries[k]));
    const Trajectory reference = partTrajectory(task, part, plan, plan_pairs);
    shooting = integrator.shoot(starts, step, plan.controls, &reference);
    pieces.clear();
    std::vector<std::vector<Eigen::VectorXd>> paths;
    for (const Trajectory& piece : shooting.steps) {
      pieces.push_back(fullSceneTrajectory(task, part, piece));
      paths.push_back(densePath(pieces.back()));
    }
    verification.modelled_pairs = static_cast<int>(part.modelled.size());
    if (shooting.status != SolveStatus::kSuccess) {
      verification.status = shooting.status;
      verification.message = "the interval re-simulation failed: " + shooting.message;
      verification.seconds = stopwatch.wallSeconds();
      return verification;
    }
    grew = modelPairsThatCameNear(task.scene, paths, margin, in_use);
  }
  verification.status = SolveStatus::kSuccess;
  verification.error = 0.0;
  for (int k = 0; k < intervals; ++k) {
    verification.interval_errors.push_back((pieces[k].finalState() - boundaries[k + 1]).norm());
    verification.error = std::max(verification.error, verification.interval_errors.back());
  }
  verification.open_loop_gain =
      largestGain(shooting.transitions, shooting.why_undefined, verification.gain_note);
  // The smallest gap of every pair in reach at the re-simulations' element boundaries.
  std::vector<ContactPair> in_reach;
  for (const PairDecision& decision : decisions) {
    if (decision.modelled || decision.checked) in_reach.push_back(decision.pair);
  }
  verification.gap = verification.relative_gap = std::numeric_limits<double>::infinity();
  for (const Trajectory& piece : pieces) {
    const std::vector<double> gaps = smallestGapsAt(task.scene, in_reach, piece.states);
    for (size_t k = 0; k < gaps.size(); ++k) {
      verification.gap = std::min(verification.gap, gaps[k]);
      verification.relative_gap =
          std::min(verification.relative_gap, gaps[k] / task.scene.pairSize(in_reach[k]));
    }
  }
  // Contacts of the re-simulation that the plan holds no force of in that interval.
  const std::vector<ContactPair> fine_pairs = modelledOf(in_use);
  const std::shared_ptr<const DcsModel> plan_model =
      plan_pairs.empty() ? nullptr : task.scene.model(plan_pairs);
  for (int row = 0; row < static_cast<int>(fine_pairs.size()); ++row) {
    const auto planned = std::find(plan_pairs.begin(), plan_pairs.end(), fine_pairs[row]);
    const int plan_row =
        planned == plan_pairs.end() ? -1 : static_cast<int>(planned - plan_pairs.begin());
    const std::vector<bool> held =
        plan_row < 0 ? std::vector<bool>(intervals, false) : heldIntervals(plan, plan_row);
    for (int k = 0; k < intervals; ++k) {
      if (held[k]) continue;
      const auto touch = std::find_if(pieces[k].elements.begin(), pieces[k].elements.end(),
                                      [&](const ElementValues& e) { return pushes(e, row); });
      if (touch == pieces[k].elements.end()) continue;
      Graze graze;
      if (plan_row >= 0) {
        graze = closestInInterval(task.scene, *plan_model->constraints(), plan_row, fine_pairs[row],
                                  plan, k, std::numeric_limits<double>::infinity());
      } else {
        graze.pair = fine_pairs[row];
        graze.interval = k;
        graze.depth = smallestGap(task.scene, fine_pairs[row], densePath(plan));
      }
      graze.time = touch->start_time;
      graze.touched = true;
      verification.grazes.push_back(graze);
    }
  }
  for (const Graze& own : planGrazes(task, plan, plan_pairs, graze_depth)) {
    const bool known = std::any_of(
        verification.grazes.begin(), verification.grazes.end(),
        [&](const Graze& g) { return g.pair == own.pair && g.interval == own.interval; });
    if (!known) verification.grazes.push_back(own);
  }
  std::sort(verification.grazes.begin(), verification.grazes.end(),
            [](const Graze& a, const Graze& b) { return a.time < b.time; });
  const OpenLoop open = open_loop.get();
  verification.open_loop = open.trajectory;
  verification.open_loop_pairs = open.pairs;
  verification.open_loop_error = open.error;
  verification.seconds = stopwatch.wallSeconds();
  return verification;
}

}  // namespace fesd
