#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/discretization/discretization.h"
#include "fesd_trajopt/solver/square_newton.h"

namespace fesd {

/// The derivatives of one simulation step's (or part's) solution with respect to its start
/// state and control: the implicit function theorem on the smooth system the step's active set
/// leaves (the equations SquareNewton solves), at the solution. FESD's element lengths are
/// unknowns of that system, so the switches move with the data and the derivatives are those of
/// the exact flow across them (Nurkanovic et al. 2024, Theorem 19).
struct StepSensitivity {
  bool defined = false;
  std::string why_undefined;
  Eigen::MatrixXd final_state;  ///< d x_end / d (x_start, u): n_x x (n_x + n_u)
  Eigen::MatrixXd steps;        ///< d h_n / d (x_start, u), one row per element
};

/// The modes a solved step shows: per element and pair, active where its multiplier side is
/// positive (beyond `tolerance`) at some stage point; a pair with both sides negligible over a
/// whole element keeps the mode it had before (at the start: `active_at_start`).
PairModes modesOf(const Trajectory& piece, const std::vector<bool>& active_at_start,
                  double tolerance);

/// Why the derivatives of a step with these modes are not defined, or "": a pair whose free side
/// (c for an inactive pair, at the stage points and between them,
/// Discretization::grazesBetweenStages; lambda for an active one) vanishes to `tolerance` in an
/// element where the pair does not switch at either end: a grazing contact, or a force that
/// falls to zero and rises again; or two pairs of different switching groups switching at one
/// element boundary (Discretization::switchingGroup). `active_before`: the modes before the step
/// (empty: none), so that a switch at its start (a release where a control jumps) counts as one.
std::string degeneracy(const Discretization& discretization, const Trajectory& piece,
                       const PairModes& modes, const std::vector<bool>& active_before,
                       double tolerance);

/// The pairs with a force at a trajectory's end (the modes before the next step).
std::vector<bool> activeAtEnd(const Trajectory& trajectory, double tolerance);

/// Why a step's end keeps its derivatives from being defined, or "": a pair with both sides
/// negligible there switches right at the end, where no element boundary is free to follow it
/// and the one-sided derivatives differ by the saltation. Not so for a pair in contact before
/// where releases are smooth (Discretization::releasesAreSmooth): no saltation.
std::string switchAtEnd(const Discretization& discretization, const Trajectory& piece,
                        const PairModes& modes, double tolerance);

/// The sensitivities of the step `discretization` holds (its start state and control set), at
/// its `solution` whose pairs take `modes`: the active set fixed at sigma = 0 (FESD: the modes'
/// zero sides and equal steps where nothing switches; fixed steps: the zero sides the solution
/// shows), then SquareNewton::derivatives. Not defined where the solution does not solve that
/// system to `tolerance`, or SquareNewton::derivatives does not define them.
StepSensitivity stepSensitivity(Discretization& discretization, const std::vector<double>& solution,
                                const PairModes& modes, int state_size, double tolerance,
                                SquareNewton& newton);

}  // namespace fesd
