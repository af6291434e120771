#pragma once

#include <string>

#include <Eigen/Dense>

namespace fesd {

/// Collocation families the discretisation supports.
enum class CollocationFamily { kRadauIIA, kGaussLegendre };

/// Butcher tableau (A, b, c) of an implicit collocation Runge-Kutta scheme.
struct ButcherTableau {
  CollocationFamily family;
  int stages;
  Eigen::MatrixXd a;
  Eigen::VectorXd b;
  Eigen::VectorXd c;

  /// True when the last stage point is the end of the step (c_{n_s} = 1), as for Radau-IIA.
  bool lastStageIsEndPoint() const;
  /// Classical order of the scheme on smooth problems.
  int order() const;
  std::string name() const;
};

/// Builds the tableau of the given family with `stages` stages (1..9). The nodes are the roots of
/// the family's Jacobi-type polynomial, polished by Newton's method in long double; A and b
/// follow from the collocation conditions C(s), B(s), so every entry is exact to the last bit
/// that double can hold. Throws std::invalid_argument outside 1..9.
ButcherTableau makeTableau(CollocationFamily family, int stages);

}  // namespace fesd
