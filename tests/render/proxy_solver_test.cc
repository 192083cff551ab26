// SPDX-License-Identifier: Apache-2.0
// Tests of the proxy LCP solver (thesis §3.2.2, eq. 3.4–3.6): analytic cases, LCP conditions
// and equality of the O(m) sweep with the dense eq. 3.6 iteration.
#include "mrh/render/proxy_solver.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "mrh/core/error.h"
#include "proxy_test_problems.h"

namespace mrh::render {
namespace {

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// Depths are ~1e-3 m and levers ~0.1 m; double rounding of f is ~1e-19 m, so 1e-14 m is far
// above noise and far below anything physical.
constexpr double kExact = 1e-14;
// The required bound for the O(m) sweep against the dense reference (m).
constexpr double kDenseAgreement = 1e-10;
// LCP residuals after convergence to kConvergence (m).
constexpr double kConvergence = 1e-14;
constexpr double kLcpTol = 1e-10;

ProxySolverSettings Converge() {
  return ProxySolverSettings{100000, kConvergence};
}

using testing::ExpectLcpConditions;
using testing::PrismFaceRows;
using testing::Problem;
using testing::RandomProblem;
using testing::Solved;
using testing::SolveFast;

TEST(ProxySolverTest, SingleContactMatchesTheClosedFormOfU1) {
  const Vec3 n = Vec3(0.2, 1.0, -0.1).normalized();
  const ProxyRow row{n, Vec3(0.03, -0.1, 0.02), 2e-3};
  const Mat3 w_inv = Vec3(1.0 / 2.0, 1.0 / 3.0, 1.0 / 4.0).asDiagonal();
  const Solved s = SolveFast({row}, w_inv, Converge());
  const Vec3 j = row.r.cross(n);
  const double f = row.rhs / (1.0 + j.dot(w_inv * j));
  EXPECT_NEAR(s.f[0], f, kExact);
  EXPECT_LT((s.dr - f * n).norm(), kExact);
  EXPECT_LT((s.dtheta - f * (w_inv * j)).norm(), kExact);
  EXPECT_NEAR(n.dot(s.dtheta.cross(row.r) + s.dr), row.rhs, kExact);
}

TEST(ProxySolverTest, SingleContactWithLeverAlongNormalTranslatesOnly) {
  const Vec3 n = Vec3::UnitY();
  const double depth = 2e-3;
  const Solved s = SolveFast({ProxyRow{n, Vec3(0, -0.1, 0), depth}}, Mat3::Identity(), Converge());
  EXPECT_LT((s.dr - depth * n).norm(), kExact);
  EXPECT_EQ(s.dtheta.norm(), 0.0);
}

TEST(ProxySolverTest, SymmetricFaceContactTranslatesByTheDepthWithoutRotation) {
  const double depth = 1e-3;
  std::vector<ProxyRow> rows;
  for (double x : {-0.1, 0.1}) {
    for (double z : {-0.1, 0.1}) rows.push_back(ProxyRow{Vec3::UnitY(), Vec3(x, -0.1, z), depth});
  }
  const Solved s = SolveFast(rows, Mat3::Identity() / 3.33, Converge());
  EXPECT_TRUE(s.result.converged);
  EXPECT_LT((s.dr - depth * Vec3::UnitY()).norm(), 1e-12);
  EXPECT_LT(s.dtheta.norm(), 1e-12);
}

TEST(ProxySolverTest, SymmetricEdgeContactTranslatesByTheDepthWithoutRotation) {
  const double depth = 1e-3;
  const double h = 0.1 * std::sqrt(2.0);
  const std::vector<ProxyRow> rows{ProxyRow{Vec3::UnitY(), Vec3(0, -h, 0.1), depth},
                                   ProxyRow{Vec3::UnitY(), Vec3(0, -h, -0.1), depth}};
  const Solved s = SolveFast(rows, Mat3::Identity() / 3.33, Converge());
  EXPECT_LT((s.dr - depth * Vec3::UnitY()).norm(), 1e-12);
  EXPECT_LT(s.dtheta.norm(), 1e-12);
}

TEST(ProxySolverTest, ConvergedSolutionSatisfiesTheLcpConditionsOnRandomProblems) {
  // Up to 6 rows, so C is generically positive definite and PGS converges in f, not only in
  // (Δr, Δθ).
  std::mt19937 rng(20120901);
  for (int trial = 0; trial < 200; ++trial) {
    const Problem p = RandomProblem(&rng, 1 + trial % 6);
    const Solved s = SolveFast(p.rows, p.w_inv, Converge());
    ASSERT_TRUE(s.result.converged) << "trial " << trial;
    ExpectLcpConditions(p, s, kLcpTol, trial);
  }
}

TEST(ProxySolverTest, LinearSweepEqualsDenseIterationOnRandomProblems) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const Problem p = RandomProblem(&rng, 1 + trial % 40);
    std::vector<double> start(p.rows.size(), 0.0);
    if (trial % 2 == 1) {
      for (double& v : start) v = 1e-3 * unit(rng);  // a warm start
    }
    const ProxySolverSettings settings{1 + trial % 60, kExact};
    const Solved fast = SolveFast(p.rows, p.w_inv, settings, start);
    std::vector<double> dense = start;
    const ProxySolveResult reference = SolveProxyDense(p.rows, p.w_inv, settings, dense);
    ASSERT_EQ(fast.result.iterations, reference.iterations) << "trial " << trial;
    EXPECT_EQ(fast.result.converged, reference.converged) << "trial " << trial;
    for (std::size_t k = 0; k < dense.size(); ++k) {
      EXPECT_NEAR(fast.f[k], dense[k], kDenseAgreement) << "trial " << trial << " row " << k;
    }
  }
}

TEST(ProxySolverTest, LinearSweepEqualsDenseIterationOnAFourHundredRowFrictionContact) {
  // A 200-gon face pressed into a floor and dragged along x and twisted: normal rows along z
  // and friction rows along the slip of each point (T3.4's shape, m = 400 rows).
  const std::vector<ProxyRow> rows = PrismFaceRows(200);
  const Mat3 w_inv = (Vec3(1.0, 2.0, 3.0).asDiagonal() * 1e-2).toDenseMatrix().inverse();
  const ProxySolverSettings settings{20, 0.0};
  const Solved fast = SolveFast(rows, w_inv, settings);
  std::vector<double> dense(rows.size(), 0.0);
  const ProxySolveResult reference = SolveProxyDense(rows, w_inv, settings, dense);
  ASSERT_EQ(fast.result.iterations, reference.iterations);
  double worst = 0.0;
  for (std::size_t k = 0; k < dense.size(); ++k) {
    worst = std::max(worst, std::abs(fast.f[k] - dense[k]));
  }
  EXPECT_LE(worst, kDenseAgreement);
}

TEST(ProxySolverTest, DisplacementIsWeightedSumOfRowsOfTheReturnedMultipliers) {
  std::mt19937 rng(3);
  const Problem p = RandomProblem(&rng, 9);
  const Solved s = SolveFast(p.rows, p.w_inv, ProxySolverSettings{7, 0.0});
  Vec3 dr = Vec3::Zero();
  Vec3 dtheta = Vec3::Zero();
  for (std::size_t k = 0; k < p.rows.size(); ++k) {  // eq. 3.2–3.3
    dr += s.f[k] * p.rows[k].a;
    dtheta += s.f[k] * (p.w_inv * p.rows[k].r.cross(p.rows[k].a));
  }
  EXPECT_LT((s.dr - dr).norm(), kExact);
  EXPECT_LT((s.dtheta - dtheta).norm(), kExact);
}

TEST(ProxySolverTest, WarmStartFromTheSolutionConvergesInOneSweep) {
  std::mt19937 rng(11);
  const Problem p = RandomProblem(&rng, 10);
  const Solved cold = SolveFast(p.rows, p.w_inv, ProxySolverSettings{100000, 1e-13});
  ASSERT_TRUE(cold.result.converged);
  ASSERT_GT(cold.result.iterations, 1);
  const Solved warm = SolveFast(p.rows, p.w_inv, ProxySolverSettings{100000, 1e-12}, cold.f);
  EXPECT_EQ(warm.result.iterations, 1);
  EXPECT_TRUE(warm.result.converged);
}

TEST(ProxySolverTest, IterationCapReportsNotConvergedWithFiniteOutput) {
  std::mt19937 rng(5);
  const Problem p = RandomProblem(&rng, 12);
  const Solved s = SolveFast(p.rows, p.w_inv, ProxySolverSettings{1, 0.0});
  EXPECT_EQ(s.result.iterations, 1);
  EXPECT_FALSE(s.result.converged);
  EXPECT_GT(s.result.max_change, 0.0);
  EXPECT_TRUE(IsFinite(s.dr) && IsFinite(s.dtheta));
}

TEST(ProxySolverTest, NoRowsGiveZeroDisplacementAndConverged) {
  const Solved s = SolveFast({}, Mat3::Identity(), ProxySolverSettings{});
  EXPECT_EQ(s.result.iterations, 0);
  EXPECT_TRUE(s.result.converged);
  EXPECT_EQ(s.dr.norm() + s.dtheta.norm(), 0.0);
}

TEST(ProxySolverTest, NegativeOrNonFiniteStartValuesStartFromZero) {
  const std::vector<ProxyRow> rows{ProxyRow{Vec3::UnitZ(), Vec3::Zero(), 1e-3}};
  const Solved s = SolveFast(rows, Mat3::Identity(), ProxySolverSettings{1, 0.0}, {-5.0});
  EXPECT_NEAR(s.f[0], 1e-3, kExact);
  const Solved t = SolveFast(rows, Mat3::Identity(), ProxySolverSettings{1, 0.0}, {NAN});
  EXPECT_NEAR(t.f[0], 1e-3, kExact);
}

TEST(ProxySolverTest, ZeroCapacityIsRejected) {
  EXPECT_THAT(
      [] {
        ProxySolver solver(0);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("capacity = 0 rows")));
}

}  // namespace
}  // namespace mrh::render
