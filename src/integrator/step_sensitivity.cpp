#include "fesd_trajopt/integrator/step_sensitivity.h"

#include <string>

#include "fesd_trajopt/integrator/active_set_step.h"

namespace fesd {

PairModes modesOf(const Trajectory& piece, const std::vector<bool>& active_at_start,
                  double tolerance) {
  PairModes modes;
  std::vector<bool> previous = active_at_start;
  for (const ElementValues& element : piece.elements) {
    const int pairs = static_cast<int>(element.stage_multipliers.rows());
    previous.resize(pairs, false);
    std::vector<bool> active(pairs);
    for (int k = 0; k < pairs; ++k) {
      const bool pushes = element.stage_multipliers.row(k).maxCoeff() > tolerance;
      const bool apart = element.stage_constraints.row(k).maxCoeff() > tolerance;
      active[k] = pushes || (!apart && previous[k]);
    }
    modes.push_back(active);
    previous = active;
  }
  return modes;
}

namespace {

/// Two pairs of different switching groups changing their mode at one element boundary inside
/// the step: under perturbation either comes first. (At a step's start a control jump pins them.)
std::string coincidingSwitches(const Discretization& discretization, const Trajectory& piece,
                               const PairModes& modes) {
  for (size_t e = 1; e < modes.size(); ++e) {
    int first = -1;
    for (int k = 0; k < static_cast<int>(modes[e].size()); ++k) {
      if (modes[e][k] == modes[e - 1][k]) continue;
      if (first < 0) {
        first = k;
      } else if (discretization.switchingGroup(k) != discretization.switchingGroup(first)) {
        return "pairs " + std::to_string(first) + " and " + std::to_string(k) +
               " switch together at t = " + std::to_string(piece.times[e]) +
               " (coinciding switches separate under perturbation)";
      }
    }
  }
  return "";
}

}  // namespace

std::string degeneracy(const Discretization& discretization, const Trajectory& piece,
                       const PairModes& modes, const std::vector<bool>& active_before,
                       double tolerance) {
  const std::string coinciding = coincidingSwitches(discretization, piece, modes);
  if (!coinciding.empty()) return coinciding;
  const int elements = static_cast<int>(piece.elements.size());
  for (int e = 0; e < elements; ++e) {
    const ElementValues& element = piece.elements[e];
    const int stages = static_cast<int>(element.stage_multipliers.cols());
    for (int k = 0; k < static_cast<int>(modes[e].size()); ++k) {
      const bool active = modes[e][k];
      const bool switch_before =
          e > 0 ? modes[e - 1][k] != active
                : k < static_cast<int>(active_before.size()) && active_before[k] != active;
      const bool switch_after = e + 1 < elements && modes[e + 1][k] != active;
      // Beside a switch of the pair its free side starts or ends at zero (a release under an
      // unchanged control lets lambda fall and c rise continuously): the switch is the event
      // the equations place, so only elements away from one are checked.
      if (switch_before || switch_after) continue;
      const std::string pair = "pair " + std::to_string(k);
      for (int j = 0; j < stages; ++j) {
        if (e + 1 == elements && j + 1 == stages) continue;  // the step's end: switchAtEnd
        const double free_side =
            active ? element.stage_multipliers(k, j) : element.stage_constraints(k, j);
        if (free_side > tolerance) continue;
        const double time = element.start_time + element.step * piece.stage_nodes(j);
        return pair + (active ? "'s force vanishes" : " touches") +
               " at t = " + std::to_string(time) + " without switching there";
      }
      if (!active && discretization.grazesBetweenStages(piece, e, k, tolerance)) {
        return pair +
               " touches between the stage points after t = " + std::to_string(element.start_time) +
               " without switching there";
      }
    }
  }
  return "";
}

std::vector<bool> activeAtEnd(const Trajectory& trajectory, double tolerance) {
  const ElementValues& last = trajectory.elements.back();
  const int stage = static_cast<int>(last.stage_multipliers.cols()) - 1;
  std::vector<bool> active;
  for (int k = 0; k < static_cast<int>(last.stage_multipliers.rows()); ++k) {
    active.push_back(last.stage_multipliers(k, stage) > tolerance);
  }
  return active;
}

std::string switchAtEnd(const Discretization& discretization, const Trajectory& piece,
                        const PairModes& modes, double tolerance) {
  const ElementValues& last = piece.elements.back();
  const int stage = static_cast<int>(last.stage_multipliers.cols()) - 1;
  for (int k = 0; k < static_cast<int>(last.stage_multipliers.rows()); ++k) {
    if (last.stage_multipliers(k, stage) > tolerance ||
        last.stage_constraints(k, stage) > tolerance) {
      continue;
    }
    if (modes.back()[k] && discretization.releasesAreSmooth()) continue;
    return "pair " + std::to_string(k) +
           " switches at the end of a step (t = " + std::to_string(piece.times.back()) +
           "), where no element boundary is free to follow it";
  }
  return "";
}

StepSensitivity stepSensitivity(Discretization& discretization, const std::vector<double>& solution,
                                const PairModes& modes, int state_size, double tolerance,
                                SquareNewton& newton) {
  StepSensitivity sensitivity;
  RelaxedMpcc& nlp = discretization.nlp();
  const double relaxation = nlp.relaxation();
  nlp.setRelaxation(0.0);
  const bool free_steps = discretization.stepsAreFree();
  const std::vector<bool> zero_sides =
      free_steps ? discretization.activeSetOf(modes) : nlp.identifyActiveSet(solution.data());
  if ((zero_sides.empty() && nlp.numComplementarities() > 0) ||
      !nlp.fixGivenActiveSet(zero_sides, solution.data())) {
    nlp.setRelaxation(relaxation);
    sensitivity.why_undefined =
        "its modes fix no active set at its solution (the big-M step equilibration's pairs have "
        "no modes)";
    return sensitivity;
  }
  std::vector<int> wanted;
  for (int d = 0; d < state_size; ++d) wanted.push_back(discretization.finalStateIndex() + d);
  const std::vector<int> steps = discretization.stepIndices();
  wanted.insert(wanted.end(), steps.begin(), steps.end());
  const SolutionDerivatives derivatives = newton.derivatives(
      nlp, solution, free_steps ? equalStepTies(discretization, modes) : std::vector<VariableTie>{},
      discretization.startAndControlVariables(), wanted);
  nlp.releaseActiveSet();
  nlp.setRelaxation(relaxation);
  if (!derivatives.defined) {
    sensitivity.why_undefined = "its active set's system: " + derivatives.failure;
    return sensitivity;
  }
  if (!(derivatives.residual <= tolerance)) {
    sensitivity.why_undefined = "its solution solves its active set's system only to " +
                                std::to_string(derivatives.residual);
    return sensitivity;
  }
  sensitivity.final_state = derivatives.values.topRows(state_size);
  sensitivity.steps = derivatives.values.bottomRows(static_cast<int>(steps.size()));
  sensitivity.defined = sensitivity.final_state.allFinite() && sensitivity.steps.allFinite();
  if (!sensitivity.defined) sensitivity.why_undefined = "its derivatives are not finite";
  return sensitivity;
}

}  // namespace fesd
