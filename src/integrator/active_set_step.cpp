#include "fesd_trajopt/integrator/active_set_step.h"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "fesd_trajopt/discretization/collocation_discretization.h"

namespace fesd {
namespace {

/// The value that must stay nonnegative for a pair in a mode: c (constraint side) when
/// inactive, lambda (multiplier side) when active.
double signedValue(const ElementValues& element, int pair, int stage, bool active) {
  return active ? element.stage_multipliers(pair, stage) : element.stage_constraints(pair, stage);
}

/// Where a pair's signs first fail: the element boundary (0 = the step's start) from which it
/// must leave the mode it had there, or boundary -1 when its signs hold.
struct Violation {
  int boundary = -1;
  bool mode = false;
};

/// The violated value's zero crossing, linearly interpolated between stage points, rounded to
/// the nearest element boundary.
Violation firstViolation(const Trajectory& piece, const PairModes& modes, int pair,
                         double tolerance) {
  const int elements = static_cast<int>(piece.elements.size());
  const double start = piece.times.front();
  const double nominal = (piece.times.back() - start) / elements;
  for (int e = 0; e < elements; ++e) {
    const ElementValues& element = piece.elements[e];
    const bool active = modes[e][pair];
    const int stages = static_cast<int>(element.stage_multipliers.cols());
    for (int j = 0; j < stages; ++j) {
      const double value = signedValue(element, pair, j, active);
      if (value >= -tolerance) continue;
      double previous = 0.0;
      if (j > 0) {
        previous = signedValue(element, pair, j - 1, active);
      } else if (e > 0) {
        previous = signedValue(piece.elements[e - 1], pair, stages - 1, active);
      }
      // Stage points taken as evenly spaced: a boundary, not a time, is what is needed.
      const double between = previous > 0.0 ? previous / (previous - value) : 0.0;
      const double time = element.start_time + element.step * (j + between) / stages;
      const int boundary = static_cast<int>(std::lround((time - start) / nominal));
      return {std::clamp(boundary, 0, std::max(0, elements - 1)), active};
    }
  }
  return {};
}

/// `jumping`: the forces its active set left free (jumpingForces), whose products are left out.
MpccReport solvedReport(const NlpAssembly& nlp, std::vector<double> solution,
                        const std::vector<int>& jumping) {
  MpccReport report;
  report.status = SolveStatus::kSuccess;
  report.message = "solved as a smooth system with its active set fixed (Newton)";
  report.complementarity_residual =
      jumping.empty() ? nlp.complementarityResidual(solution.data())
                      : nlp.complementarityResidualOfUnknowns(solution.data(), jumping);
  report.objective = nlp.objective(solution.data());
  report.solution = std::move(solution);
  report.polished = true;
  report.b_stationary = true;  // a simulation step has no objective to descend
  return report;
}

}  // namespace

std::vector<VariableTie> equalStepTies(const Discretization& discretization,
                                       const PairModes& modes) {
  const auto* collocation = dynamic_cast<const CollocationDiscretization*>(&discretization);
  if (!collocation || !collocation->stepsAreFree()) return {};
  std::vector<VariableTie> ties;
  for (int e = 1; e < collocation->numElements() && e < static_cast<int>(modes.size()); ++e) {
    if (!collocation->startsInterval(e) && modes[e - 1] == modes[e]) {
      ties.push_back({collocation->stepIndex(e - 1), collocation->stepIndex(e)});
    }
  }
  return ties;
}

PairModes predictModes(const Trajectory* previous, const std::vector<bool>& active_at_start,
                       int num_elements, double tolerance) {
  std::vector<bool> active = active_at_start;
  if (previous && !previous->elements.empty()) {
    const ElementValues& last = previous->elements.back();
    const int stage = static_cast<int>(last.stage_multipliers.cols()) - 1;
    active.assign(last.stage_multipliers.rows(), false);
    for (int k = 0; k < static_cast<int>(active.size()); ++k) {
      active[k] = last.stage_constraints(k, stage) <= tolerance &&
                  last.stage_multipliers(k, stage) > tolerance;
    }
  }
  return PairModes(num_elements, active);
}

ActiveSetStep solveByActiveSets(Discretization& discretization, const std::vector<double>& guess,
                                const PairModes& predicted, const ActiveSetOptions& options) {
  SquareNewton newton;
  return solveByActiveSets(discretization, guess, predicted, options, newton);
}

ActiveSetStep solveByActiveSets(Discretization& discretization, const std::vector<double>& guess,
                                const PairModes& predicted, const ActiveSetOptions& options,
                                SquareNewton& newton) {
  const double tolerance = options.tolerance;
  NlpAssembly& nlp = discretization.nlp();
  ActiveSetStep step;
  PairModes modes = predicted;
  std::vector<int> switched_at_start;  ///< pairs the last mode change switched at the start
  nlp.setRelaxation(0.0);
  while (step.mode_sequences < options.max_sequences) {
    ++step.mode_sequences;
    const std::vector<bool> zero_sides = discretization.activeSetOf(modes);
    if (zero_sides.empty() && nlp.numComplementarities() > 0) {
      step.failure = "the NLP has pairs the modes do not decide";
      return step;
    }
    const std::vector<int> jumping = discretization.jumpingForces(modes);
    if (!nlp.fixGivenActiveSet(zero_sides, guess.data(), jumping)) {
      // A switch estimated at the step's start where the start's data (c, or the force carried
      // over from the previous step) forbids one: it happens in the first element instead.
      bool moved = false;
      for (int pair : switched_at_start) {
        if (modes.size() > 1 && modes[0][pair] != modes[1][pair]) continue;
        modes[0][pair] = !modes[0][pair];
        moved = true;
      }
      switched_at_start.clear();
      if (moved) continue;
      step.failure = "the modes contradict the data at the step's start";
      return step;
    }
    std::vector<double> x = guess;
    const NewtonResult solved = newton.solve(nlp, x, equalStepTies(discretization, modes));
    nlp.releaseActiveSet();
    step.newton_iterations += solved.iterations;
    if (!solved.converged) {
      step.failure = "Newton: " + solved.failure;
      return step;
    }
    Trajectory piece = discretization.extract(
        x.data(), options.start_time, options.activity_tolerance, options.penetration_tolerance);
    PairModes next = modes;
    bool signs_hold = true;
    switched_at_start.clear();
    for (int pair = 0; pair < static_cast<int>(modes.front().size()); ++pair) {
      const Violation violation = firstViolation(piece, modes, pair, tolerance);
      if (violation.boundary < 0) continue;
      signs_hold = false;
      discretization.switchPair(next, pair, violation.boundary, violation.mode);
      if (violation.boundary == 0) switched_at_start.push_back(pair);
    }
    if (signs_hold) {
      // A jumping force's couples hold a product its active set leaves (jumpingForces).
      const double violation = constraintViolation(nlp, x, nlp.complementarityRowsWith(jumping));
      // The start's data within kNegligibleFixedValue of zero counts as zero, as it did when
      // the active set was fixed: a contact met at the step's start (its gap -1e-10 there, from
      // the step before) leaves a product with its force that no unknown can lower.
      // A force left free where it jumps (jumpingForces) leaves its products out.
      const double residual = nlp.complementarityResidualOfUnknowns(x.data(), jumping);
      if (violation <= tolerance && residual <= tolerance) {
        step.outcome =
            modes == predicted ? ActiveSetOutcome::kPredicted : ActiveSetOutcome::kLocated;
        step.report = solvedReport(nlp, std::move(x), jumping);
        step.piece = std::move(piece);
        step.modes = std::move(modes);
        return step;
      }
      std::ostringstream failure;
      failure << "a bound or row is violated by " << violation << ", complementarity by "
              << residual;
      step.failure = failure.str();
      return step;
    }
    if (next == modes) {
      step.failure = "the violated signs suggest no other modes";
      return step;
    }
    modes = std::move(next);
  }
  step.failure = "no mode sequence within " + std::to_string(options.max_sequences) + " tries";
  return step;
}

}  // namespace fesd
