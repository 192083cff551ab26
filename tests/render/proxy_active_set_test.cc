// SPDX-License-Identifier: Apache-2.0
// Tests of the exact active-set proxy solver: KKT conditions of the LCP (eq. 3.4), agreement with
// converged PGS, analytic cases (one contact, symmetric contacts, rotational friction), warm
// start, caps, infeasibility.
#include "mrh/render/proxy_active_set.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "mrh/core/error.h"
#include "mrh/render/proxy_solver.h"
#include "proxy_test_problems.h"
#include "support/alloc_guard.h"

namespace mrh::render {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// Depths ~1e-3 m, levers ~0.1 m: rounding of Δr and f is ~1e-18 m; 1e-13 m is far above it.
constexpr double kExact = 1e-13;
// LCP residual bounds on random problems (m).
constexpr double kLcpTol = 1e-11;

using testing::ExpectLcpConditions;
using testing::PrismFaceRows;
using testing::Problem;
using testing::RandomProblem;
using testing::Solved;
using testing::SolveExact;
using testing::SolveFast;

// f >= 0, w = C f − rhs >= −tol, min(f, w) <= tol per row, and (Δr, Δθ) = W⁻¹Jᵀf: the KKT
// conditions, sufficient for the optimum of the convex program, so they prove the solution.
void ExpectKkt(const Problem& p, const Solved& s, double tol, int trial) {
  ExpectLcpConditions(p, s, tol, trial);
  Vec3 dr = Vec3::Zero();
  Vec3 dtheta = Vec3::Zero();
  for (std::size_t k = 0; k < p.rows.size(); ++k) {
    dr += s.f[k] * p.rows[k].a;
    dtheta += s.f[k] * (p.w_inv * p.rows[k].r.cross(p.rows[k].a));
  }
  EXPECT_LT((s.dr - dr).norm(), tol) << "trial " << trial;
  EXPECT_LT((s.dtheta - dtheta).norm(), 10 * tol) << "trial " << trial;
}

TEST(ProxyActiveSetTest, SingleContactMatchesTheClosedFormOfU1) {
  const Vec3 n = Vec3(0.2, 1.0, -0.1).normalized();
  const ProxyRow row{n, Vec3(0.03, -0.1, 0.02), 2e-3};
  const Mat3 w_inv = Vec3(1.0 / 2.0, 1.0 / 3.0, 1.0 / 4.0).asDiagonal();
  const Solved s = SolveExact({row}, w_inv);
  const Vec3 j = row.r.cross(n);
  const double f = row.rhs / (1.0 + j.dot(w_inv * j));
  EXPECT_TRUE(s.result.converged);
  EXPECT_EQ(s.result.iterations, 1);
  EXPECT_NEAR(s.f[0], f, kExact);
  EXPECT_LT((s.dr - f * n).norm(), kExact);
  EXPECT_LT((s.dtheta - f * (w_inv * j)).norm(), kExact);
}

TEST(ProxyActiveSetTest, SymmetricFaceContactTranslatesByTheDepthWithoutRotationU2) {
  const double depth = 1e-3;
  std::vector<ProxyRow> rows;
  for (double x : {-0.1, 0.1}) {
    for (double z : {-0.1, 0.1}) rows.push_back(ProxyRow{Vec3::UnitY(), Vec3(x, -0.1, z), depth});
  }
  const Solved s = SolveExact(rows, Mat3::Identity() / 3.33);
  EXPECT_TRUE(s.result.converged);
  EXPECT_LE(s.result.iterations, 4);  // three independent rows span the face's three modes
  EXPECT_LT((s.dr - depth * Vec3::UnitY()).norm(), kExact);
  EXPECT_LT(s.dtheta.norm(), kExact);
}

TEST(ProxyActiveSetTest, OpposedFrictionRowsGiveTheAnalyticTwistAtTheT32Weight) {
  // Two contacts ±l along x slipping ∓ along y: rotational friction about z. By symmetry
  // Δr = 0 and Δθ = (σ/l) z, with f_1 + f_2 = σ R_zz / l² (eq. 3.3). PGS needs ~R_zz/l² sweeps
  // per decade here (1e6); the exact solver needs two steps.
  const double l = 0.05, sigma = 5e-4;
  const Mat3 weight = Vec3(8420.0, 1670.0, 8420.0).asDiagonal();
  const std::vector<ProxyRow> rows{ProxyRow{Vec3::UnitY(), Vec3(l, 0, 0), sigma},
                                   ProxyRow{-Vec3::UnitY(), Vec3(-l, 0, 0), sigma}};
  const Solved s = SolveExact(rows, weight.inverse());
  EXPECT_TRUE(s.result.converged);
  EXPECT_LT(s.dr.norm(), kExact);
  EXPECT_NEAR(s.dtheta.z(), sigma / l, 1e-12);
  EXPECT_NEAR(s.f[0] + s.f[1], sigma * 8420.0 / (l * l), 1e-6);

  const Solved pgs = SolveFast(rows, weight.inverse(), {50, 1e-10});
  EXPECT_FALSE(pgs.result.converged);           // why the exact solver exists
  EXPECT_LT(pgs.dtheta.z(), 0.01 * sigma / l);  // 50 sweeps reach under 1 % of the twist
}

TEST(ProxyActiveSetTest, SatisfiesTheLcpConditionsOnRandomProblems) {
  std::mt19937 rng(20121001);
  for (int trial = 0; trial < 300; ++trial) {
    // 1..60 rows, so most problems are redundant (more rows than 6 degrees of freedom), and
    // R_w from 1e-2 to 1e4 m² (thesis weights are 3.33 and 8420).
    const Problem p = RandomProblem(&rng, 1 + trial % 60, -2.0, 6.0);
    const Solved s = SolveExact(p.rows, p.w_inv, {200, 1e-14});
    ASSERT_TRUE(s.result.converged) << "trial " << trial;
    EXPECT_LE(std::count_if(s.f.begin(), s.f.end(),
                            [](double v) {
                              return v > 0.0;
                            }),
              6);
    ExpectKkt(p, s, kLcpTol, trial);
  }
}

TEST(ProxyActiveSetTest, EqualsConvergedPgsDisplacementOnWellConditionedProblems) {
  // Where PGS does converge (R_w ~ |r|²), both give the unique (Δr, Δθ) of the LCP.
  std::mt19937 rng(99);
  int compared = 0;
  for (int trial = 0; trial < 100; ++trial) {
    const Problem p = RandomProblem(&rng, 1 + trial % 12, -2.0, 0.5);
    const Solved exact = SolveExact(p.rows, p.w_inv);
    const Solved pgs = SolveFast(p.rows, p.w_inv, {100000, 1e-16});
    if (!pgs.result.converged) continue;  // a rare slow case; the KKT test covers correctness
    ++compared;
    EXPECT_LT((exact.dr - pgs.dr).norm(), 1e-11) << "trial " << trial;
    EXPECT_LT((exact.dtheta - pgs.dtheta).norm(), 1e-10) << "trial " << trial;
  }
  EXPECT_GE(compared, 90);
}

TEST(ProxyActiveSetTest, WarmStartFromTheSolutionTakesNoSteps) {
  std::mt19937 rng(11);
  const Problem p = RandomProblem(&rng, 30, 0.0, 3.0);
  const Solved cold = SolveExact(p.rows, p.w_inv);
  ASSERT_TRUE(cold.result.converged);
  ASSERT_GT(cold.result.iterations, 1);
  const Solved warm = SolveExact(p.rows, p.w_inv, {64, 1e-13}, cold.f);
  EXPECT_TRUE(warm.result.converged);
  EXPECT_EQ(warm.result.iterations, 0);
  EXPECT_LT((warm.dr - cold.dr).norm(), kExact);
  EXPECT_LT((warm.dtheta - cold.dtheta).norm(), kExact);
}

TEST(ProxyActiveSetTest, WarmStartWithWrongRowsStillReachesTheSolution) {
  std::mt19937 rng(12);
  const Problem p = RandomProblem(&rng, 20, 0.0, 3.0);
  const Solved cold = SolveExact(p.rows, p.w_inv);
  std::vector<double> start(p.rows.size(), 0.0);
  for (std::size_t k = 0; k < start.size(); k += 2) start[k] = 1e-3;  // any rows at all
  const Solved warm = SolveExact(p.rows, p.w_inv, {64, 1e-14}, start);
  EXPECT_TRUE(warm.result.converged);
  EXPECT_LT((warm.dr - cold.dr).norm(), 1e-12);
  EXPECT_LT((warm.dtheta - cold.dtheta).norm(), 1e-11);
}

TEST(ProxyActiveSetTest, ContradictoryRowsReportNotConvergedWithFiniteOutput) {
  // a·Δr >= 1 mm and −a·Δr >= 1 mm at the same point cannot both hold.
  const std::vector<ProxyRow> rows{ProxyRow{Vec3::UnitZ(), Vec3::Zero(), 1e-3},
                                   ProxyRow{-Vec3::UnitZ(), Vec3::Zero(), 1e-3}};
  const Solved s = SolveExact(rows, Mat3::Identity());
  EXPECT_FALSE(s.result.converged);
  EXPECT_TRUE(IsFinite(s.dr) && IsFinite(s.dtheta));
}

TEST(ProxyActiveSetTest, StepCapReportsNotConvergedWithFiniteOutput) {
  std::mt19937 rng(5);
  const Problem p = RandomProblem(&rng, 12, 0.0, 1.0);
  const Solved s = SolveExact(p.rows, p.w_inv, {1, 0.0});
  EXPECT_EQ(s.result.iterations, 1);
  EXPECT_FALSE(s.result.converged);
  EXPECT_GT(s.result.max_change, 0.0);
  EXPECT_TRUE(IsFinite(s.dr) && IsFinite(s.dtheta));
}

TEST(ProxyActiveSetTest, NoRowsGiveZeroDisplacementAndConverged) {
  const Solved s = SolveExact({}, Mat3::Identity());
  EXPECT_EQ(s.result.iterations, 0);
  EXPECT_TRUE(s.result.converged);
  EXPECT_EQ(s.dr.norm() + s.dtheta.norm(), 0.0);
}

TEST(ProxyActiveSetTest, ThousandPointFaceWithFrictionConvergesInFewSteps) {
  // T3.4's shape: a 1000-gon prism base pressed into a floor, dragged and twisted.
  const std::vector<ProxyRow> rows = PrismFaceRows(1000);
  const Mat3 w_inv = (Vec3(8420.0, 1670.0, 8420.0).asDiagonal().toDenseMatrix()).inverse();
  const Problem p{rows, w_inv};
  const Solved s = SolveExact(rows, w_inv, {64, 1e-12});
  ASSERT_TRUE(s.result.converged);
  EXPECT_LE(s.result.iterations, 30);
  // Every row holds to the tolerance (the KKT conditions over 2000 rows).
  ExpectKkt(p, s, 1e-10, 0);
}

TEST(ProxyActiveSetTest, SolveDoesNotAllocate) {
  std::mt19937 rng(8);
  const Problem p = RandomProblem(&rng, 40, 0.0, 3.0);
  ProxyActiveSetSolver solver(64);
  std::vector<double> f(p.rows.size(), 0.0);
  Vec3 dr, dtheta;
  mrh::testing::AllocGuard guard;
  for (int i = 0; i < 10; ++i) {
    (void)solver.Solve(p.rows, p.w_inv, {64, 1e-12}, f, &dr, &dtheta);
  }
  EXPECT_EQ(guard.count(), 0);
}

TEST(ProxyActiveSetTest, ZeroCapacityIsRejected) {
  EXPECT_THAT(
      [] {
        ProxyActiveSetSolver solver(0);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("capacity = 0")));
}

}  // namespace
}  // namespace mrh::render
