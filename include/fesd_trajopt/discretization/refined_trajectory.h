#pragma once

#include <vector>

#include <Eigen/Dense>

#include "fesd_trajopt/discretization/trajectory.h"

namespace fesd {

/// A solution moved onto a finer grid of the same control intervals, as the start of a solve
/// there (the accuracy ladder's next rung starts from the plan it has): interval k's elements
/// split into interval_elements[k] (at least as many as it has) by dividing each into equal
/// parts, the longest elements first getting the extra parts, so that every element boundary
/// of the solution, and with it every switch, stays a boundary. States at the new stage nodes
/// (the tableau's c, `stage_nodes`) and boundaries come from each element's collocation
/// polynomial; multipliers from the polynomial through its stage multipliers (clipped at 0);
/// stage constraint values are left at 0 and switches out (the discretisation's guess completes
/// them). Throws std::invalid_argument for a count below an interval's elements.
Trajectory refinedTrajectory(const Trajectory& solution, const std::vector<int>& interval_elements,
                             const Eigen::VectorXd& stage_nodes);

/// A trajectory from the start of control interval `first` on, as a trajectory of its own: times
/// from 0, intervals counted from `first`, the controls before it dropped (a replan after `first`
/// intervals of the plan were executed starts from it). Throws std::invalid_argument for an
/// interval it does not have.
Trajectory laterPart(const Trajectory& trajectory, int first);

/// The elements of each control interval of a trajectory.
std::vector<int> elementsPerInterval(const Trajectory& trajectory);

}  // namespace fesd
