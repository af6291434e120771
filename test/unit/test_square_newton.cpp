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
  int x, y, z, inequality;
  Parabola() {
    x = nlp.addVariables(1, -kInf, kInf);
    y = nlp.addVariables(1, 0.0, kInf);
    z = nlp.addVariables(1, 5.0, 5.0);
    const int curve = nlp.addRows(1, 3.0, 3.0);
    nlp.addLinear(curve, y, 1.0);
    nlp.addFunctionTerm(fesd::makeAutoDiffFunction(1, 1, Square{}), {x}, -1, {{curve, 1.0}});
    const int line = nlp.addRows(1, -1.0, -1.0);
    nlp.addLinear(line, {{x, 1.0}, {y, -1.0}});
    inequality = nlp.addRows(1, -kInf, 1.5);
    nlp.addLinear(inequality, y, 1.0);
    nlp.finalize();
  }
};

TEST(SquareNewton, ConvergesQuadraticallyToTheNearRootAndSetsFixedVariables) {
  Parabola problem;
  std::vector<double> x{2.0, 2.0, 0.0};
  const fesd::NewtonResult result = fesd::solveSquareSystem(problem.nlp, x);
  ASSERT_TRUE(result.converged) << result.failure;
  EXPECT_NEAR(x[0], 1.0, 1e-14);
  EXPECT_NEAR(x[1], 2.0, 1e-14);
  EXPECT_EQ(x[2], 5.0);
  EXPECT_LE(result.residual, 1e-12);
  EXPECT_LE(result.iterations, 7);  // quadratic convergence from 1 away
  // Newton does not impose the inequality row: y = 2 > 1.5 is reported by the check.
  EXPECT_NEAR(fesd::constraintViolation(problem.nlp, x), 0.5, 1e-12);
  // The other root violates y >= 0 by 1.
  std::vector<double> far{-3.0, -2.0, 0.0};
  ASSERT_TRUE(fesd::solveSquareSystem(problem.nlp, far).converged);
  EXPECT_NEAR(far[0], -2.0, 1e-12);
  EXPECT_NEAR(fesd::constraintViolation(problem.nlp, far), 1.0, 1e-12);
}

TEST(SquareNewton, RefusesNonSquareSystemsAndReportsSingularJacobians) {
  Parabola problem;
  problem.nlp.setRowBounds(problem.inequality, 1.0, 1.0);  // a third equation for two unknowns
  std::vector<double> x{2.0, 2.0, 0.0};
  fesd::NewtonResult result = fesd::solveSquareSystem(problem.nlp, x);
  EXPECT_FALSE(result.converged);
  EXPECT_EQ(result.iterations, 0);
  EXPECT_NE(result.failure.find("not square"), std::string::npos) << result.failure;

  Parabola tangent;
  std::vector<double> at_vertex{-0.5, 0.5, 0.0};  // 2x = -1: the rows' gradients are parallel
  result = fesd::solveSquareSystem(tangent.nlp, at_vertex);
  EXPECT_FALSE(result.converged);
  EXPECT_NE(result.failure.find("singular"), std::string::npos) << result.failure;
}

}  // namespace
