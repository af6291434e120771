// Newton's method on the square system of an NLP's equality rows in its free variables
// (solver/square_newton.cpp), and the feasibility measure used to accept its result.
#include <cmath>
#include <vector>

#include <gtest/gtest.h>

#include "fesd_trajopt/function/autodiff_function.h"
#include "fesd_trajopt/nlp/nlp_assembly.h"
#include "fesd_trajopt/solver/square_newton.h"

namespace {

constexpr double kInf = fesd::NlpAssembly::kInfinity;

struct Square {
  template <class T>
  void operator()(const T* z, T* r) const {
    r[0] = z[0] * z[0];
  }
};

/// x^2 + y = 3 and x - y = -1, with z fixed at 5 and an inequality row y <= 1.5: the roots are
/// (1, 2) and (-2, -1).
struct Parabola {
  fesd::NlpAssembly nlp;
  int x, y, z, line, inequality;
  Parabola() {
    x = nlp.addVariables(1, -kInf, kInf);
    y = nlp.addVariables(1, 0.0, kInf);
    z = nlp.addVariables(1, 5.0, 5.0);
    const int curve = nlp.addRows(1, 3.0, 3.0);
    nlp.addLinear(curve, y, 1.0);
    nlp.addFunctionTerm(fesd::makeAutoDiffFunction(1, 1, Square{}), {x}, -1, {{curve, 1.0}});
    line = nlp.addRows(1, -1.0, -1.0);
    nlp.addLinear(line, {{x, 1.0}, {y, -1.0}});
    inequality = nlp.addRows(1, -kInf, 1.5);
    nlp.addLinear(inequality, y, 1.0);
    nlp.finalize();
  }
};

TEST(SquareNewton, ConvergesToTheNearRootAndSetsFixedVariables) {
  Parabola problem;
  std::vector<double> x{2.0, 2.0, 0.0};
  const fesd::NewtonResult result = fesd::solveSquareSystem(problem.nlp, x);
  ASSERT_TRUE(result.converged) << result.failure;
  // To the tolerance (1e-12): the last steps reuse a Jacobian (the chord method).
  EXPECT_NEAR(x[0], 1.0, 1e-13);
  EXPECT_NEAR(x[1], 2.0, 1e-13);
  EXPECT_EQ(x[2], 5.0);
  EXPECT_LE(result.residual, 1e-12);
  EXPECT_EQ(result.factorizations, 2);  // at the start, and where the chord slowed down
  EXPECT_LE(result.iterations, 12);
  // Newton does not impose the inequality row: y = 2 > 1.5 is reported by the check.
  EXPECT_NEAR(fesd::constraintViolation(problem.nlp, x), 0.5, 1e-12);
  // The other root violates y >= 0 by 1.
  std::vector<double> far{-3.0, -2.0, 0.0};
  ASSERT_TRUE(fesd::solveSquareSystem(problem.nlp, far).converged);
  EXPECT_NEAR(far[0], -2.0, 1e-12);
  EXPECT_NEAR(fesd::constraintViolation(problem.nlp, far), 1.0, 1e-12);
}

TEST(SquareNewton, SolvesMoreEquationsThanUnknownsOnlyWhenTheyAgree) {
  // A third equation y = 2 agrees with the root (1, 2): Newton on two of the rows finds it.
  Parabola agreeing;
  agreeing.nlp.setRowBounds(agreeing.inequality, 2.0, 2.0);
  std::vector<double> x{2.0, 2.0, 0.0};
  fesd::NewtonResult result = fesd::solveSquareSystem(agreeing.nlp, x);
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_NEAR(x[0], 1.0, 1e-13);
  EXPECT_NEAR(x[1], 2.0, 1e-13);
  // y = 1 does not: the steps settle on a root of two rows, the third stays violated by 1.
  Parabola disagreeing;
  disagreeing.nlp.setRowBounds(disagreeing.inequality, 1.0, 1.0);
  x = {2.0, 2.0, 0.0};
  result = fesd::solveSquareSystem(disagreeing.nlp, x);
  EXPECT_FALSE(result.converged);
  EXPECT_GT(result.iterations, 0);
  EXPECT_NEAR(result.residual, 1.0, 1e-9);
  EXPECT_NE(result.failure.find("disagree"), std::string::npos) << result.failure;
}

TEST(SquareNewton, TiesMakeAnUnderdeterminedSystemSquareAndOtherwiseItIsRefused) {
  Parabola free_line;
  free_line.nlp.setRowBounds(free_line.line, -kInf, kInf);  // x^2 + y = 3: a curve of roots
  std::vector<double> x{2.0, 2.0, 0.0};
  fesd::NewtonResult result = fesd::solveSquareSystem(free_line.nlp, x);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_NE(result.failure.find("not square"), std::string::npos) << result.failure;
  // Tied, x = y: x^2 + x = 3.
  fesd::SquareNewton newton;
  result = newton.solve(free_line.nlp, x, {{free_line.x, free_line.y}});
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_EQ(result.added_ties, 1);
  EXPECT_NEAR(x[0], (std::sqrt(13.0) - 1.0) / 2.0, 1e-14);
  EXPECT_NEAR(x[1], x[0], 1e-15);
  // A tie on a fixed variable is no tie.
  result = newton.solve(free_line.nlp, x, {{free_line.x, free_line.z}});
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.added_ties, 0);
}

TEST(SquareNewton, SkipsTiesThatARowImposesAlready) {
  // x - y = 0 and x + z = 1 in three unknowns: the tie (x, y) is that row, (y, z) is new.
  fesd::NlpAssembly nlp;
  const int x = nlp.addVariables(1, -kInf, kInf), y = nlp.addVariables(1, -kInf, kInf),
            z = nlp.addVariables(1, -kInf, kInf);
  nlp.addLinear(nlp.addRows(1, 0.0, 0.0), {{x, 1.0}, {y, -1.0}});
  nlp.addLinear(nlp.addRows(1, 1.0, 1.0), {{x, 1.0}, {z, 1.0}});
  nlp.finalize();
  std::vector<double> point{0.0, 0.0, 0.0};
  const fesd::NewtonResult result = fesd::SquareNewton().solve(nlp, point, {{x, y}, {y, z}});
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_EQ(result.added_ties, 1);
  EXPECT_NEAR(point[0], 0.5, 1e-15);
  EXPECT_NEAR(point[1], 0.5, 1e-15);
  EXPECT_NEAR(point[2], 0.5, 1e-15);
}

TEST(SquareNewton, ReportsSingularJacobians) {
  Parabola tangent;
  std::vector<double> at_vertex{-0.5, 0.5, 0.0};  // 2x = -1: the rows' gradients are parallel
  const fesd::NewtonResult result = fesd::solveSquareSystem(tangent.nlp, at_vertex);
  EXPECT_FALSE(result.converged);
  EXPECT_NE(result.failure.find("singular"), std::string::npos) << result.failure;
}

TEST(SquareNewton, ANewSolveOfTheSameSystemStartsWithTheLastFactorisation) {
  Parabola problem;
  fesd::SquareNewton newton;
  std::vector<double> first{2.0, 2.0, 0.0};
  ASSERT_TRUE(newton.solve(problem.nlp, first).converged);
  // Near the root the Jacobian there serves all steps; a solver of its own factorises once.
  std::vector<double> reused{1.01, 1.01, 0.0}, fresh{1.01, 1.01, 0.0};
  const fesd::NewtonResult again = newton.solve(problem.nlp, reused);
  const fesd::NewtonResult alone = fesd::solveSquareSystem(problem.nlp, fresh);
  ASSERT_TRUE(again.converged && alone.converged);
  EXPECT_EQ(again.factorizations, 0);
  EXPECT_EQ(alone.factorizations, 1);
  EXPECT_NEAR(reused[0], 1.0, 1e-13);
  EXPECT_NEAR(fresh[0], 1.0, 1e-13);
  // Near the other root the old Jacobian (of the first root) makes no progress: the solver
  // factorises anew and converges there too.
  std::vector<double> other{-2.2, 0.2, 0.0};
  const fesd::NewtonResult switched = newton.solve(problem.nlp, other);
  ASSERT_TRUE(switched.converged) << switched.failure;
  EXPECT_GE(switched.factorizations, 1);
  EXPECT_NEAR(other[0], -2.0, 1e-12);
}

/// x^2 + y = p and x - y = -1 with the parameter p a fixed variable: at a root,
/// dx/dp = dy/dp = 1 / (2 x + 1).
struct ParametricParabola {
  fesd::NlpAssembly nlp;
  int x, y, p;
  /// extra_row: none, or 2 x - 2 y = -2 (the line again: one equation too many).
  enum ExtraRow { kNone, kSameLine };
  explicit ParametricParabola(double parameter, ExtraRow extra_row = kNone) {
    x = nlp.addVariables(1, -kInf, kInf);
    y = nlp.addVariables(1, -kInf, kInf);
    p = nlp.addVariables(1, parameter, parameter);
    const int curve = nlp.addRows(1, 0.0, 0.0);
    nlp.addLinear(curve, {{y, 1.0}, {p, -1.0}});
    nlp.addFunctionTerm(fesd::makeAutoDiffFunction(1, 1, Square{}), {x}, -1, {{curve, 1.0}});
    const int line = nlp.addRows(1, -1.0, -1.0);
    nlp.addLinear(line, {{x, 1.0}, {y, -1.0}});
    if (extra_row == kSameLine) nlp.addLinear(nlp.addRows(1, -2.0, -2.0), {{x, 2.0}, {y, -2.0}});
    nlp.finalize();
  }
};

TEST(SquareNewton, DerivativesAtARootAreThoseOfTheImplicitFunction) {
  ParametricParabola problem(3.0);
  std::vector<double> point{0.5, 0.5, 3.0};
  fesd::SquareNewton newton;
  ASSERT_TRUE(newton.solve(problem.nlp, point).converged);
  EXPECT_NEAR(point[problem.x], 1.0, 1e-12);
  const fesd::SolutionDerivatives derivatives =
      newton.derivatives(problem.nlp, point, {}, {problem.p}, {problem.x, problem.y, problem.p});
  ASSERT_TRUE(derivatives.defined) << derivatives.failure;
  EXPECT_LT(derivatives.residual, 1e-12);
  EXPECT_NEAR(derivatives.values(0, 0), 1.0 / 3.0, 1e-12);  // the root is exact to 1e-12
  EXPECT_NEAR(derivatives.values(1, 0), 1.0 / 3.0, 1e-12);
  EXPECT_EQ(derivatives.values(2, 0), 1.0);  // a fixed variable: its own derivative
  // Against central differences of the root.
  const double h = 1e-6;
  std::vector<double> up{1.0, 2.0, 3.0 + h}, down{1.0, 2.0, 3.0 - h};
  ParametricParabola above(3.0 + h), below(3.0 - h);
  ASSERT_TRUE(newton.solve(above.nlp, up).converged);
  ASSERT_TRUE(newton.solve(below.nlp, down).converged);
  EXPECT_NEAR((up[problem.x] - down[problem.x]) / (2 * h), derivatives.values(0, 0), 1e-8);
}

TEST(SquareNewton, DerivativesOfMoreEquationsThanUnknownsComeFromThePivotRows) {
  ParametricParabola problem(3.0, ParametricParabola::kSameLine);
  std::vector<double> point{0.5, 0.5, 3.0};
  fesd::SquareNewton newton;
  ASSERT_TRUE(newton.solve(problem.nlp, point).converged);
  const fesd::SolutionDerivatives derivatives =
      newton.derivatives(problem.nlp, point, {}, {problem.p}, {problem.x});
  ASSERT_TRUE(derivatives.defined) << derivatives.failure;
  EXPECT_NEAR(derivatives.values(0, 0), 1.0 / 3.0, 1e-12);
}

TEST(SquareNewton, DerivativesWhereTheJacobianIsSingularAreNotDefined) {
  // At x = -1/2 the curve's tangent is parallel to the line: 2 x + 1 = 0.
  ParametricParabola problem(0.75);
  const std::vector<double> point{-0.5, 0.5, 0.75};
  fesd::SquareNewton newton;
  const fesd::SolutionDerivatives derivatives =
      newton.derivatives(problem.nlp, point, {}, {problem.p}, {problem.x});
  EXPECT_FALSE(derivatives.defined);
  EXPECT_EQ(derivatives.failure, "singular Jacobian");
}

}  // namespace
