// Our LDL^T behind Ipopt's HSL loader (solver/ipopt_linear_solver.cpp): the MA97 calls as Ipopt
// 3.11.9 makes them (info fields, inertia, singular and non-finite matrices, calls out of
// order), and whole Ipopt solves with it against MUMPS, alone and in parallel threads.
#include <cmath>
#include <random>
#include <thread>
#include <vector>

#include <gtest/gtest.h>
#include <Eigen/Dense>

#include "fesd_trajopt/function/autodiff_function.h"
#include "fesd_trajopt/nlp/nlp_assembly.h"
#include "fesd_trajopt/solver/kkt_capture.h"
#include "fesd_trajopt/solver/mpcc_solver.h"
#include "solver/ipopt_linear_solver.h"
#include "solver/ipopt_session.h"
#include "support/sparse_matrices.h"

namespace {

namespace ma97 = fesd::ma97;

/// A KKT matrix in Ipopt's layout (primal block first, constraint rows last, those with nothing
/// below their diagonal), as 1-based compressed columns.
struct IpoptMatrix {
  int n;
  std::vector<int> ptr, row;
  std::vector<double> val;
  Eigen::MatrixXd dense;
};

IpoptMatrix fromDense(const Eigen::MatrixXd& kkt) {
  const fesd_test::LowerMatrix lower = fesd_test::lowerMatrix(kkt);  // keeps every diagonal
  IpoptMatrix matrix{static_cast<int>(kkt.rows()), {}, {}, lower.values, kkt};
  for (int start : lower.pattern.column_starts) matrix.ptr.push_back(start + 1);
  for (int r : lower.pattern.rows) matrix.row.push_back(r + 1);
  return matrix;
}

/// [H J^T; J 0] with a random sparse H (positive definite if `convex`) and J of full row rank.
IpoptMatrix ipoptLayout(int primal, int constraints, bool convex, uint32_t seed) {
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(primal + constraints, primal + constraints);
  std::mt19937 generator(seed);
  std::uniform_real_distribution<double> value(-1.0, 1.0);
  for (int j = 0; j < primal; ++j) {
    for (int i = j + 1; i < primal; ++i) {
      if (value(generator) > 0.8) kkt(i, j) = kkt(j, i) = value(generator);
    }
    kkt(j, j) = convex ? 4.0 + primal * 0.2 : value(generator);
  }
  for (int r = 0; r < constraints; ++r) {
    kkt(primal + r, r % primal) = kkt(r % primal, primal + r) = 1.0 + 0.5 * value(generator);
    const int other = (r * 7 + 3) % primal;
    kkt(primal + r, other) = kkt(other, primal + r) += value(generator);
  }
  return fromDense(kkt);
}

/// The control Ipopt 3.11.9 sets before its calls.
ma97::Control ipoptControl() {
  ma97::Control control;
  ma97::defaultControl(&control);
  control.f_arrays = 1;
  control.action = 0;
  control.u = 1e-8;
  control.small = 1e-20;
  return control;
}

/// The members of Ipopt 3.11.9's Ma97SolverInterface around akeep_, as the compiler laid them
/// out (ndim_ in the tail padding of its base class).
struct InterfaceLayout {
  int base_tail;
  int ndim;
  const double* val;
  int numneg;
  int numdelay;
  void* akeep;
};

TEST(Ma97Bridge, AnalyseFactorSolveAsIpoptCallsThem) {
  const IpoptMatrix m = ipoptLayout(30, 12, true, 1);
  const ma97::Control control = ipoptControl();
  ma97::Info info;
  InterfaceLayout owner{};  // akeep a member of an object, as in Ipopt's (val never matches)
  void*& akeep = owner.akeep;
  void* fkeep = nullptr;
  ma97::analyse(0, m.n, m.ptr.data(), m.row.data(), nullptr, &akeep, &control, &info, nullptr);
  ASSERT_EQ(info.flag, 0);
  ASSERT_NE(akeep, nullptr);
  EXPECT_TRUE(info.ordering == 1 || info.ordering == 3);
  EXPECT_GE(info.num_factor, static_cast<long>(m.val.size()));
  EXPECT_GT(info.maxfront, 0);
  ma97::factor(4, m.ptr.data(), m.row.data(), m.val.data(), &akeep, &fkeep, &control, &info,
               nullptr);
  ASSERT_EQ(info.flag, 0);
  ASSERT_NE(fkeep, nullptr);
  EXPECT_EQ(info.num_neg, 12);  // convex primal block: one negative eigenvalue per constraint
  EXPECT_EQ(info.matrix_rank, m.n);
  Eigen::VectorXd x = m.dense * Eigen::VectorXd::Ones(m.n);
  ma97::Info solve_info;
  ma97::solve(0, 1, x.data(), m.n, &akeep, &fkeep, &control, &solve_info);
  EXPECT_EQ(solve_info.flag, 0);
  EXPECT_EQ(solve_info.num_neg, 12);  // Ipopt reads the inertia from the solve
  EXPECT_LT((x - Eigen::VectorXd::Ones(m.n)).lpNorm<Eigen::Infinity>(), 1e-9);
  // The same structure with other values reuses the factor object.
  std::vector<double> scaled = m.val;
  for (double& v : scaled) v *= 2.0;
  void* same = fkeep;
  ma97::factor(4, m.ptr.data(), m.row.data(), scaled.data(), &akeep, &fkeep, &control, &info,
               nullptr);
  EXPECT_EQ(fkeep, same);
  x = m.dense * Eigen::VectorXd::Ones(m.n);
  ma97::solve(0, 1, x.data(), m.n, &akeep, &fkeep, &control, &solve_info);
  EXPECT_LT((x - 0.5 * Eigen::VectorXd::Ones(m.n)).lpNorm<Eigen::Infinity>(), 1e-9);
  ma97::finalise(&akeep, &fkeep);
  EXPECT_EQ(akeep, nullptr);
  EXPECT_EQ(fkeep, nullptr);
}

TEST(Ma97Bridge, ReportsSingularNonFiniteAndOutOfOrderCalls) {
  // [2I J^T; J 0] with two equal constraint rows: singular (Ipopt then adds delta_c).
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(9, 9);
  kkt.topLeftCorner(6, 6) = 2.0 * Eigen::MatrixXd::Identity(6, 6);
  Eigen::MatrixXd jacobian(3, 6);
  jacobian << 1, 1, 0, 0, 0, 0, 1, 1, 0, 0, 0, 0, 0, 0, 1, 1, 0, 0;
  kkt.bottomLeftCorner(3, 6) = jacobian;
  kkt.topRightCorner(6, 3) = jacobian.transpose();
  const IpoptMatrix m = fromDense(kkt);
  const std::vector<int>& ptr = m.ptr;
  const std::vector<int>& row = m.row;
  const ma97::Control control = ipoptControl();
  ma97::Info info;
  InterfaceLayout owner{};  // akeep a member of an object, as in Ipopt's (val never matches)
  void*& akeep = owner.akeep;
  void* fkeep = nullptr;
  ma97::analyse(0, m.n, ptr.data(), row.data(), nullptr, &akeep, &control, &info, nullptr);
  ASSERT_EQ(info.flag, 0);
  ma97::factor(4, ptr.data(), row.data(), m.val.data(), &akeep, &fkeep, &control, &info, nullptr);
  EXPECT_EQ(info.flag, -7);
  EXPECT_EQ(info.matrix_rank, m.n - 1);
  std::vector<double> nan = m.val;
  nan[0] = std::nan("");
  ma97::factor(4, ptr.data(), row.data(), nan.data(), &akeep, &fkeep, &control, &info, nullptr);
  EXPECT_LT(info.flag, 0);
  EXPECT_NE(info.flag, -7);  // not singular: fatal for the step (Ipopt's restoration)
  Eigen::VectorXd x = Eigen::VectorXd::Ones(m.n);
  ma97::solve(0, 1, x.data(), m.n, &akeep, &fkeep, &control, &info);
  EXPECT_LT(info.flag, 0);  // no usable factors
  ma97::solve(1, 1, x.data(), m.n, &akeep, &fkeep, &control, &info);
  EXPECT_LT(info.flag, 0);  // only job 0 (A x = b) is supported
  ma97::finalise(&akeep, &fkeep);
  void* missing = nullptr;
  ma97::factor(4, ptr.data(), row.data(), m.val.data(), &missing, &fkeep, &control, &info, nullptr);
  EXPECT_LT(info.flag, 0);  // factor before analyse
  EXPECT_EQ(fkeep, nullptr);
  const int broken_ptr[] = {1, 1, 2};
  const int broken_row[] = {1};
  ma97::analyse(0, 2, broken_ptr, broken_row, nullptr, &akeep, &control, &info, nullptr);
  EXPECT_LT(info.flag, 0);
  EXPECT_EQ(akeep, nullptr);
}

TEST(Ma97Bridge, WritesAnIdentityScalingWhenAskedForOne) {
  const IpoptMatrix m = ipoptLayout(8, 3, true, 3);
  ma97::Control control = ipoptControl();
  control.scaling = 1;
  ma97::Info info;
  InterfaceLayout owner{};  // akeep a member of an object, as in Ipopt's (val never matches)
  void*& akeep = owner.akeep;
  void* fkeep = nullptr;
  std::vector<double> scale(m.n, -1.0);
  ma97::analyse(0, m.n, m.ptr.data(), m.row.data(), nullptr, &akeep, &control, &info, nullptr);
  ma97::factor(4, m.ptr.data(), m.row.data(), m.val.data(), &akeep, &fkeep, &control, &info,
               scale.data());
  EXPECT_EQ(info.flag, 0);
  for (double s : scale) EXPECT_EQ(s, 1.0);
  ma97::finalise(&akeep, &fkeep);
}

/// min (x0 - 1)^2 + 10 (x1 - x0^2)^2 + x2^2  s.t.  x0 + x1 + x2 = 1.5,  x0 x2 >= 0.1, x >= -5:
/// nonconvex (Ipopt corrects the inertia) with equality and inequality rows.
struct SmallNlp {
  fesd::NlpAssembly nlp;
  SmallNlp() {
    const int x = nlp.addVariables(3, -5.0, 5.0, 0.5);
    nlp.addFunctionTerm(fesd::makeAutoDiffFunction(3, 1,
                                                   [](const auto* z, auto* f) {
                                                     f[0] = (z[0] - 1.0) * (z[0] - 1.0) +
                                                            10.0 * (z[1] - z[0] * z[0]) *
                                                                (z[1] - z[0] * z[0]) +
                                                            z[2] * z[2];
                                                   }),
                        {x, x + 1, x + 2}, -1, {{fesd::NlpAssembly::kObjective, 1.0}});
    const int sum = nlp.addRows(1, 1.5, 1.5);
    nlp.addLinear(sum, {{x, 1.0}, {x + 1, 1.0}, {x + 2, 1.0}});
    const int product = nlp.addRows(1, 0.1, fesd::NlpAssembly::kInfinity);
    nlp.addFunctionTerm(
        fesd::makeAutoDiffFunction(2, 1, [](const auto* z, auto* f) { f[0] = z[0] * z[1]; }),
        {x, x + 2}, -1, {{product, 1.0}});
    nlp.finalize();
  }
  fesd::MpccReport solve(const std::string& linear_solver) {
    fesd::HomotopyOptions options;
    options.ipopt.linear_solver = linear_solver;
    return fesd::MpccSolver(options).solve(nlp, {0.5, 0.5, 0.5});
  }
};

TEST(Ma97Bridge, TellsTheInertiaOnlyToTheLayoutItKnows) {
  const double values[3] = {1.0, 2.0, 3.0};
  InterfaceLayout known{0, 3, values, -12345, 0, nullptr};
  EXPECT_TRUE(ma97::tellIpoptTheInertia(&known.akeep, values, 3, 7));
  EXPECT_EQ(known.numneg, 7);
  InterfaceLayout other_values{0, 3, nullptr, -12345, 0, nullptr};
  EXPECT_FALSE(ma97::tellIpoptTheInertia(&other_values.akeep, values, 3, 7));
  EXPECT_EQ(other_values.numneg, -12345);
  InterfaceLayout other_dimension{0, 4, values, -12345, 0, nullptr};
  EXPECT_FALSE(ma97::tellIpoptTheInertia(&other_dimension.akeep, values, 3, 7));
  EXPECT_EQ(other_dimension.numneg, -12345);
}

TEST(Ma97Bridge, IpoptsInterfaceObjectHasThatLayout) {
  // A warm start from a point of negative curvature: the first factorisations have too many
  // negative pivots, before any solve (where Ipopt would read an uninitialised count).
  SmallNlp problem;
  fesd::IpoptSettings settings;
  settings.linear_solver = fesd::kLdltSolver;
  fesd::IpoptSession session(settings);
  fesd::PrimalDualPoint point;
  point.x = {0.1, 2.0, -0.6};
  point.bound_lower_multipliers.assign(3, 1e-3);
  point.bound_upper_multipliers.assign(3, 1e-3);
  point.constraint_multipliers.assign(2, 0.0);
  point.has_multipliers = true;
  fesd::KktCapture capture(1);
  const fesd::NlpOutcome outcome = session.solve(problem.nlp, point, {});
  ASSERT_TRUE(fesd::IpoptSession::converged(outcome.status));
  ASSERT_EQ(capture.matrices().size(), 1u);
  EXPECT_GT(capture.matrices().front().negative_pivots, 2);  // two constraint rows
  EXPECT_GT(capture.totals().factorisations, 0);
  EXPECT_EQ(capture.totals().inertia_told, capture.totals().factorisations);
}

TEST(Ma97Bridge, IpoptSolvesAsWithMumps) {
  SmallNlp problem;
  const fesd::MpccReport ours = problem.solve(fesd::kLdltSolver);
  const fesd::MpccReport mumps = problem.solve("mumps");
  ASSERT_EQ(ours.status, fesd::SolveStatus::kSuccess) << ours.message;
  ASSERT_EQ(mumps.status, fesd::SolveStatus::kSuccess) << mumps.message;
  EXPECT_NEAR(ours.objective, mumps.objective, 1e-10);
  for (int i = 0; i < 3; ++i) EXPECT_NEAR(ours.solution[i], mumps.solution[i], 1e-8);
  EXPECT_NEAR(ours.iterations, mumps.iterations, 2);
}

TEST(Ma97Bridge, ParallelSolvesGiveTheSerialAnswer) {
  SmallNlp reference;
  const fesd::MpccReport serial = reference.solve(fesd::kLdltSolver);
  ASSERT_EQ(serial.status, fesd::SolveStatus::kSuccess);
  constexpr int kThreads = 4, kSolves = 20;
  std::vector<int> identical(kThreads, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < kThreads; ++t) {
    threads.emplace_back([&, t] {
      SmallNlp problem;
      for (int k = 0; k < kSolves; ++k) {
        const fesd::MpccReport report = problem.solve(fesd::kLdltSolver);
        identical[t] += report.status == serial.status && report.solution == serial.solution &&
                        report.iterations == serial.iterations;
      }
    });
  }
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < kThreads; ++t) EXPECT_EQ(identical[t], kSolves) << "thread " << t;
}

}  // namespace
