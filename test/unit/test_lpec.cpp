// The LPEC (the MPCC linearised at a branch NLP's solution, in a trust region) on tiny MPCCs
// whose B-stationarity is known.
#include <gtest/gtest.h>

#include "fesd_trajopt/solver/lpec.h"
#include "support/corner_mpcc.h"

namespace {

constexpr double kInf = fesd::NlpAssembly::kInfinity;

/// The corner MPCC (support/corner_mpcc.h) and its LPEC at a point on a given branch.
struct Corner {
  fesd_test::CornerMpcc<> mpcc;
  fesd::NlpAssembly& nlp;
  explicit Corner(double target_y) : mpcc(target_y), nlp(mpcc.nlp) { nlp.finalize(); }
  fesd::LpecResult lpec(const std::vector<double>& point, bool x_is_zero, double radius) {
    EXPECT_TRUE(nlp.fixGivenActiveSet({x_is_zero}, point.data()));
    const fesd::LpecResult result = fesd::Lpec(nlp, point, {}, 1e-6).solve(radius);
    nlp.releaseActiveSet();
    return result;
  }
};

TEST(Lpec, CertifiesAMinimiserWhoseOtherSideCannotVanish) {
  Corner corner(1.0);
  // (1, 0) with y fixed: x = 1 is far from zero within the radius, so no binary is needed and the
  // LP's value is grad f^T d = -2 dy with dy = 0.
  const fesd::LpecResult result = corner.lpec({1.0, 0.0}, false, 1e-3);
  ASSERT_TRUE(result.solved) << result.message;
  EXPECT_TRUE(result.certified);
  EXPECT_EQ(result.undecided_pairs, 0);
  EXPECT_NEAR(result.value, 0.0, 1e-12);
  EXPECT_EQ(result.left_is_zero, std::vector<bool>{false});
}

TEST(Lpec, FindsTheDescentOfTheOtherBranchAtABiactivePoint) {
  Corner corner(-1.0);
  // min (x-1)^2 + (y+1)^2: on the branch x = 0 the solution is the origin (y at its bound), which
  // is not B-stationary: with y = 0 instead, x may grow, and grad_x f = -2.
  const double radius = 1e-3;
  const fesd::LpecResult result = corner.lpec({0.0, 0.0}, true, radius);
  ASSERT_TRUE(result.solved) << result.message;
  EXPECT_FALSE(result.certified);
  EXPECT_TRUE(result.other_branch);
  EXPECT_EQ(result.undecided_pairs, 1);
  EXPECT_NEAR(result.value, -2.0 * radius, 1e-12);
  EXPECT_EQ(result.left_is_zero, std::vector<bool>{false});  // next: y = 0, x free
}

TEST(Lpec, CertifiesABiactiveMinimiser) {
  Corner corner(-1.0);
  // min (x-1)^2 + (y+1)^2 at (1, 0) on its branch y = 0, where the LPEC of the test before
  // leads: the minimiser (y's bound holds it against its gradient).
  const fesd::LpecResult result = corner.lpec({1.0, 0.0}, false, 1e-3);
  ASSERT_TRUE(result.solved);
  EXPECT_TRUE(result.certified);
  EXPECT_NEAR(result.value, 0.0, 1e-12);
}

/// min -x  s.t.  y = x,  0 <= x _|_ y >= 0: the origin is the only feasible point, B-stationary,
/// but no multiplier of the branch x = 0 shows it (biactiveDescent reports -1); the LPEC does.
TEST(Lpec, CertifiesWhereTheMultiplierTestCannot) {
  fesd_test::OnlyTheOrigin problem;
  fesd::NlpAssembly& nlp = problem.nlp;
  nlp.finalize();
  const std::vector<double> origin = {0.0, 0.0};
  ASSERT_TRUE(nlp.fixGivenActiveSet({true}, origin.data()));
  const std::vector<double> multipliers(nlp.numConstraints(), 1.0);  // d L / dx = -1 - 1
  EXPECT_GT(nlp.biactiveDescent(origin.data(), multipliers.data()), 0.0);
  const fesd::LpecResult result = fesd::Lpec(nlp, origin, multipliers, 1e-6).solve(1e-2);
  ASSERT_TRUE(result.solved) << result.message;
  EXPECT_LT(result.dual_bound, 0.0);  // the multipliers cannot tell: the MILP decides
  EXPECT_TRUE(result.certified) << result.message;
  EXPECT_NEAR(result.value, 0.0, 1e-12);
}

TEST(Lpec, TheTrustRegionDecidesWhichPairsAreUndecided) {
  Corner corner(1.0);
  // At (0, 0.01) on the branch x = 0 the other side, y = 0.01, can vanish only with a radius of
  // at least 0.01.
  EXPECT_EQ(corner.lpec({0.0, 0.01}, true, 1e-3).undecided_pairs, 0);
  const fesd::LpecResult wide = corner.lpec({0.0, 0.01}, true, 0.1);
  EXPECT_EQ(wide.undecided_pairs, 1);
  ASSERT_TRUE(wide.solved);
  // grad f = (-2, -1.98). The other branch (y to 0, x to 0.1) offers -0.2 + 0.0198; this one
  // (y up by 0.1) -0.198, the better: a point that is no branch NLP's solution.
  EXPECT_NEAR(wide.value, -1.98 * 0.1, 1e-12);
  EXPECT_FALSE(wide.certified);
  EXPECT_FALSE(wide.other_branch);
  EXPECT_EQ(wide.left_is_zero, std::vector<bool>{true});
}

TEST(Lpec, TheMultipliersOfAKktPointCertifyWithoutAnLp) {
  Corner corner(1.0);
  const std::vector<double> point = {1.0, 0.0};
  ASSERT_TRUE(corner.nlp.fixGivenActiveSet({false}, point.data()));
  // The only row is the pair's product, dropped by the fixed active set: multiplier 0.
  const fesd::Lpec lpec(corner.nlp, point, {0.0}, 1e-6);
  corner.nlp.releaseActiveSet();
  const fesd::LpecResult result = lpec.solve(1e-3);
  EXPECT_TRUE(result.certified) << result.message;
  EXPECT_EQ(result.dual_bound, 0.0);
  // At the origin on the branch x = 0 the reduced cost of x is -2: the bound says -2 radius, and
  // the MILP confirms the descent.
  Corner other(-1.0);
  const std::vector<double> origin = {0.0, 0.0};
  ASSERT_TRUE(other.nlp.fixGivenActiveSet({true}, origin.data()));
  const fesd::LpecResult descent = fesd::Lpec(other.nlp, origin, {0.0}, 1e-6).solve(1e-3);
  other.nlp.releaseActiveSet();
  EXPECT_NEAR(descent.dual_bound, -2e-3, 1e-15);
  EXPECT_FALSE(descent.certified);
  EXPECT_NEAR(descent.value, -2e-3, 1e-12);
}

TEST(Lpec, APointThatDoesNotSolveItsBranchShowsDescentOnItsOwnBranch) {
  Corner corner(1.0);
  // (0.5, 0) on the branch y = 0 is no solution of that branch (x wants to reach 1): without
  // the KKT conditions to trust, the LP finds grad_x f^T d = -1 * radius there.
  const std::vector<double> point = {0.5, 0.0};
  ASSERT_TRUE(corner.nlp.fixGivenActiveSet({false}, point.data()));
  const fesd::LpecResult result = fesd::Lpec(corner.nlp, point, {}, 1e-6).solve(1e-3);
  corner.nlp.releaseActiveSet();
  ASSERT_TRUE(result.solved) << result.message;
  EXPECT_EQ(result.undecided_pairs, 0);
  EXPECT_NEAR(result.value, -1e-3, 1e-12);
  EXPECT_FALSE(result.certified);
  EXPECT_FALSE(result.other_branch);
}

}  // namespace
