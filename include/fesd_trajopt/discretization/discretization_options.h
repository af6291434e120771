#pragma once

#include <vector>

#include "fesd_trajopt/discretization/butcher_tableau.h"
#include "fesd_trajopt/nlp/nlp_assembly.h"

namespace fesd {

/// How the cross-complementarity conditions (Pozharskiy et al. 2024, eq. 8) are imposed.
enum class CrossComplementarity {
  kElementSums,  ///< one product of sums per element and constraint (few, denser rows)
  kStagePairs,   ///< one product per pair of points (many, sparser rows)
};

/// Step equilibration of a Filippov system (Nurkanovic et al. 2024, eq. 31): (h_n - h_{n-1}) eta_n
/// = 0 with the switch indicator eta_n, or with tanh(eta_n) for a better scaling; or none (the
/// steps are then free wherever nothing switches). A PDS always uses its own exact form.
enum class StepEquilibration { kNone, kIndicator, kTanhIndicator };

/// How a PDS discretisation imposes step equilibration (Pozharskiy et al. 2024, Sec. III-C).
enum class PdsStepEquilibration {
  /// Relaxed NLPs carry only the vanishing step regulariser; active-set polishing imposes the
  /// combinatorial meaning of Table I exactly: h_{n-1} = h_n at every boundary without a switch.
  /// Measured on the showcase (N = 40): a third of the variables, half of the rows and 320 of
  /// the 560 complementarity pairs are the paper's auxiliaries, and dropping them from the
  /// relaxed NLPs cut an Ipopt iteration from about 37 ms to 12 ms with the same iterations.
  kPolishing,
  /// The paper's formulation in every NLP: nu from the KKT conditions of the max LP (auxiliary
  /// variables and complementarity pairs) and the big-M bound |h_{n-1} - h_n| <= nu M.
  kBigM,
};

/// What only the PDS discretisation (PdsDiscretization) reads.
struct PdsOptions {
  PdsStepEquilibration step_equilibration = PdsStepEquilibration::kPolishing;
  /// kBigM only: M of the bound |h_{n-1} - h_n| <= nu_n M, in units of h0. At a release
  /// c leaves the boundary quadratically, so nu is only O(delta^2) when the element after it is
  /// delta long, and M must exceed h0 / delta^2 for every delta the grid may need. With active-
  /// set polishing (MpccSolver) nu is exactly 0 away from switches, so a large M costs no
  /// equality there; in the relaxed NLPs the vanishing regulariser keeps the steps equal.
  double equilibration_big_m = 1e9;
};

/// What only the Filippov (Stewart) discretisation reads.
struct FilippovOptions {
  StepEquilibration step_equilibration = StepEquilibration::kIndicator;
  /// r of the relaxed step equilibration |((h_n - h_{n-1}) / h0) eta_n| <= r sigma. With r = 1
  /// the relaxed NLPs of example (47) on coarse grids, whose switch starts inside an element,
  /// could not move their steps and ended infeasible; with r = 1e3 some simulation steps of OCP
  /// (61)'s controls that leave a sliding mode did. So the relaxed NLPs are guided by the step
  /// regulariser (DiscretizationOptions::step_regularization), like the PDS's big M, and
  /// polishing imposes eq. 31 exactly (h_{n-1} = h_n wherever eta_n cannot vanish).
  double equilibration_relaxation = 1e6;
};

/// A constraint of a PDS kept nonnegative at a point of an element's collocation polynomial
/// between its stage points: where a plan passes a body by without a force, its polynomial can
/// cut into it between stage points that all keep clear (a graze).
struct GapGuard {
  int element;      ///< global index
  int constraint;   ///< the model's constraint (pair) index
  double fraction;  ///< of the element's length, in (0, 1)
};

/// Options of both discretisations; the nested structs hold what only one of them reads.
struct DiscretizationOptions {
  CollocationFamily family = CollocationFamily::kRadauIIA;
  int num_stages = 2;
  int num_elements = 2;  ///< finite elements per control interval
  /// Elements per control interval where they differ between intervals (the accuracy ladder
  /// refines the intervals it blames); empty: num_elements in every interval.
  std::vector<int> interval_elements;
  bool switch_detection = true;  ///< FESD; false gives the standard fixed-step method
  CrossComplementarity cross_complementarity = CrossComplementarity::kElementSums;
  double step_bound = 1.0;  ///< gamma_h: (1 - gamma_h) h0 <= h_n <= (1 + gamma_h) h0
  PdsOptions pds;
  FilippovOptions filippov;
  /// PDS only: constraints kept >= 0 between stage points.
  std::vector<GapGuard> gap_guards;
  /// rho of the regulariser  rho * sigma * sum_n ((h_n - h_{n-1}) / h0)^2  within each control
  /// interval. The relaxed NLPs (sigma > 0) leave the steps partly free; this keeps their path
  /// away from collapsed elements. At sigma -> 0 it vanishes and only the exact step
  /// equilibration remains. 0 switches it off.
  double step_regularization = 1.0;
  /// How many threads evaluate the NLP's functions (the same bits on one or two).
  NlpAssembly::Threads evaluation_threads = NlpAssembly::Threads::kMeasured;
};

}  // namespace fesd
