// SPDX-License-Identifier: Apache-2.0
// Tests of the pressure split: analytic patches, the optimality (KKT) conditions checked with a
// dual certificate the test computes itself, warm start = cold start, no allocation.
#include "mrh/render/pressure_split.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <cstdio>
#include <random>
#include <vector>

#include "mrh/core/error.h"
#include "support/alloc_guard.h"

namespace mrh::render {
namespace {

struct Point {
  Vec3 a, r;
  double depth;
  bool one_sided = true;
};

// An n × n grid of normal rows on the square [−h, h]² at height z (levers from the origin).
std::vector<Point> Patch(int n, double h, double z, double depth) {
  std::vector<Point> points;
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) {
      const double u = -h + 2 * h * i / (n - 1), v = -h + 2 * h * j / (n - 1);
      points.push_back({Vec3::UnitZ(), Vec3(u, v, z), depth});
    }
  }
  return points;
}

// Patch(n, h, 0, depth_a) and Patch(n, h, 0, depth_b) moved by `offset`.
std::vector<Point> TwoPatches(int n, double h, double depth_a, double depth_b, const Vec3& offset) {
  auto points = Patch(n, h, 0.0, depth_a);
  for (auto& p : Patch(n, h, 0.0, depth_b)) {
    p.r += offset;
    points.push_back(p);
  }
  return points;
}

void Load(const std::vector<Point>& points, PressureSplit* split) {
  split->Begin();
  for (const Point& p : points) ASSERT_TRUE(split->AddRow(p.a, p.r, p.depth, p.one_sided));
}

struct Carried {
  Vec3 f = Vec3::Zero(), tau = Vec3::Zero();
};

Carried CarriedBy(const std::vector<Point>& points, const PressureSplit& split) {
  Carried c;
  for (std::size_t k = 0; k < points.size(); ++k) {
    c.f += split.lambda(k) * points[k].a;
    c.tau += split.lambda(k) * points[k].r.cross(points[k].a);
  }
  return c;
}

// KKT of min Σλ²/δ s.t. Σλw = W, λ >= 0: some y with λ_k = δ_k (w_k·y) where λ_k > 0 and
// w_k·y <= 0 where λ_k = 0. The test finds y by least squares on the loaded rows (it does not
// ask the solver) and returns the worst violation, relative to max λ/δ.
double KktViolation(const std::vector<Point>& points, const PressureSplit& split) {
  std::vector<int> loaded;
  double scale = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    if (split.lambda(k) > 0.0 || !points[k].one_sided) loaded.push_back(static_cast<int>(k));
    scale = std::max(scale, std::abs(split.lambda(k)) / points[k].depth);
  }
  const auto w_of = [&](std::size_t k) {
    Eigen::Matrix<double, 6, 1> w;
    w << points[k].a, points[k].r.cross(points[k].a);
    return w;
  };
  Eigen::MatrixXd m(loaded.size(), 6);
  Eigen::VectorXd b(loaded.size());
  for (std::size_t i = 0; i < loaded.size(); ++i) {
    const auto k = static_cast<std::size_t>(loaded[i]);
    m.row(static_cast<Eigen::Index>(i)) = w_of(k).transpose();
    b[static_cast<Eigen::Index>(i)] = split.lambda(k) / points[k].depth;
  }
  const Eigen::VectorXd y = m.completeOrthogonalDecomposition().solve(b);
  double worst = 0.0;
  for (std::size_t k = 0; k < points.size(); ++k) {
    const double s = w_of(k).dot(y);
    const double lambda = split.lambda(k) / points[k].depth;
    const bool on = lambda > 0.0 || !points[k].one_sided;
    worst = std::max(worst, on ? std::abs(s - lambda) : std::max(0.0, s));
  }
  return worst / std::max(scale, 1e-300);
}

TEST(PressureSplit, ACentredPushOnAnEvenPatchIsAnEvenPressure) {
  const auto points = Patch(5, 0.04, -0.01, 1e-3);
  PressureSplit split(points.size());
  Load(points, &split);
  const auto result = split.Solve(Vec3(0, 0, 2.5), Vec3::Zero());
  EXPECT_TRUE(result.converged);
  EXPECT_EQ(result.active, points.size());
  // The ridge (1e-8 of the trace, pressure_split.h) carries W (1 − 1e-8): 1e-9 N of 0.1 N.
  for (std::size_t k = 0; k < points.size(); ++k) EXPECT_NEAR(split.lambda(k), 0.1, 2e-9);
}

// A moment within the patch's reach (centre of pressure 1 cm off centre, no row lifts off): the
// pressure is linear in position; checked in the sums, by KKT and row by row.
TEST(PressureSplit, AMomentWithinReachIsALinearPressureCarryingItExactly) {
  const auto points = Patch(9, 0.05, 0.0, 2e-3);
  PressureSplit split(points.size());
  Load(points, &split);
  // Centre of pressure 1 cm off in −y: τ = r × F with r = (0, −0.01, 0), F = 4 N up.
  const Vec3 f(0, 0, 4.0), tau = Vec3(0, -0.01, 0).cross(f);
  ASSERT_TRUE(split.Solve(f, tau).converged);
  const Carried c = CarriedBy(points, split);
  EXPECT_LT((c.f - f).norm(), 1e-7);
  EXPECT_LT((c.tau - tau).norm(), 1e-8);
  EXPECT_LT(KktViolation(points, split), 1e-9);
  // Linear in v: the rows at equal v carry equal loads, and the load falls linearly with v.
  const double l0 = split.lambda(0), l1 = split.lambda(1), l2 = split.lambda(2);
  EXPECT_NEAR(l1 - l0, l2 - l1, 1e-9);
  EXPECT_LT(l1, l0);  // v grows with j: less load away from the centre of pressure
  EXPECT_NEAR(split.lambda(9), l0, 1e-9);
}

// A centre of pressure near the edge: part of the patch lifts off (λ = 0 there) and the rest
// carries the wrench; the certificate proves it optimal.
TEST(PressureSplit, APatchPartlyLiftsOffUnderALargeMoment) {
  const auto points = Patch(11, 0.05, 0.0, 1e-3);
  PressureSplit split(points.size());
  Load(points, &split);
  const Vec3 f(0, 0, 3.0), tau = Vec3(0.04, 0, 0).cross(f);
  const auto result = split.Solve(f, tau);
  ASSERT_TRUE(result.converged);
  EXPECT_LT(result.active, points.size());
  EXPECT_GT(result.active, points.size() / 4);
  const Carried c = CarriedBy(points, split);
  EXPECT_LT((c.f - f).norm(), 1e-7);
  EXPECT_LT((c.tau - tau).norm(), 1e-8);
  EXPECT_LT(KktViolation(points, split), 1e-9);
}

// Two patches at different depths and heights, random wrenches within reach, with rows of
// several directions (friction-like): each solve meets the KKT conditions.
TEST(PressureSplit, RandomWrenchesOverTwoPatchesMeetTheOptimalityConditions) {
  std::mt19937 rng(14);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto points = TwoPatches(6, 0.04, 1e-3, 2e-3, Vec3(0.15, 0.02, 0.01));
  const std::size_t normals = points.size();
  for (std::size_t k = 0; k < normals; k += 2) {  // tangential rows on every other point
    points.push_back({Vec3(1, 0, 0), points[k].r, points[k].depth});
    points.push_back({Vec3(0, -1, 0), points[k].r, points[k].depth});
  }
  PressureSplit split(points.size());
  for (int trial = 0; trial < 50; ++trial) {
    Load(points, &split);
    if (trial % 3 == 0) split.Reset();
    const Vec3 f(0.5 * std::abs(u(rng)), -0.5 * std::abs(u(rng)), 2.0 + u(rng));
    const Vec3 cop(0.075 + 0.08 * u(rng), 0.01 + 0.03 * u(rng), 0.0);
    const Vec3 tau = cop.cross(f);
    const auto result = split.Solve(f, tau);
    ASSERT_TRUE(result.converged) << "trial " << trial;
    EXPECT_LT(KktViolation(points, split), 1e-8) << "trial " << trial;
    const Carried c = CarriedBy(points, split);
    EXPECT_LT((c.f - f).norm(), 1e-6) << "trial " << trial;
  }
}

// Two-sided tangent rows (points with friction) carry a sideways force of either sign, all of
// it, and the normal rows still only push.
TEST(PressureSplit, TwoSidedTangentRowsCarrySidewaysForcesEitherWay) {
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  auto points = TwoPatches(5, 0.04, 1e-3, 1e-3, Vec3(0.12, 0.0, 0.0));
  const std::size_t normals = points.size();
  for (std::size_t k = 0; k < normals; ++k) {
    points.push_back({Vec3(1, 0, 0), points[k].r, points[k].depth, false});
    points.push_back({Vec3(0, 1, 0), points[k].r, points[k].depth, false});
  }
  PressureSplit split(points.size());
  for (int trial = 0; trial < 30; ++trial) {
    Load(points, &split);
    const Vec3 f(u(rng), u(rng), 3.0 + u(rng));
    const Vec3 tau = Vec3(0.06 + 0.05 * u(rng), 0.02 * u(rng), 0.0).cross(f);
    ASSERT_TRUE(split.Solve(f, tau).converged) << "trial " << trial;
    const Carried c = CarriedBy(points, split);
    EXPECT_LT((c.f - f).norm(), 1e-6) << "trial " << trial;
    EXPECT_LT((c.tau - tau).norm(), 1e-7) << "trial " << trial;
    EXPECT_LT(KktViolation(points, split), 1e-8) << "trial " << trial;
    for (std::size_t k = 0; k < normals; ++k) EXPECT_GE(split.lambda(k), 0.0);
  }
}

// A tangent plane is two two-sided rows along orthonormal tangents at each of its points,
// summed, and a normal group is its rows: two tilted patches with their own normals, loaded
// both ways, give the same normal λ and the same per-patch tangential wrench (and that wrench
// lies in the plane), with the normals as plain rows and as groups.
TEST(PressureSplit, ATangentPlaneIsTwoTangentRowsAPoint) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const Vec3 normals[2] = {Vec3(0.1, 0.0, 1.0).normalized(), Vec3(-0.7, 0.2, 0.7).normalized()};
  std::vector<Point> rows;  // normal rows of both patches, then each point's two tangents
  std::vector<int> patch_of;
  for (int patch = 0; patch < 2; ++patch) {
    const Vec3 n = normals[patch];
    const Vec3 e1 = n.unitOrthogonal(), e2 = n.cross(e1);
    for (int i = 0; i < 16; ++i) {
      const Vec3 r = Vec3(0.05 * patch, 0.0, 0.02) + 0.03 * u(rng) * e1 + 0.03 * u(rng) * e2;
      rows.push_back({n, r, 1e-3 * (1.2 + u(rng))});
      patch_of.push_back(patch);
    }
  }
  const std::size_t normal_rows = rows.size();
  for (std::size_t k = 0; k < normal_rows; ++k) {
    const Vec3 n = normals[patch_of[k]];
    const double angle = 3.0 * u(rng);  // any tangent basis
    const Vec3 t1 =
        std::cos(angle) * n.unitOrthogonal() + std::sin(angle) * n.cross(n.unitOrthogonal());
    rows.push_back({t1, rows[k].r, rows[k].depth, false});
    rows.push_back({n.cross(t1), rows[k].r, rows[k].depth, false});
  }
  PressureSplit explicit_rows(rows.size()), planes(normal_rows, 2), grouped(normal_rows, 2);
  for (int trial = 0; trial < 20; ++trial) {
    Load(rows, &explicit_rows);
    planes.Begin();
    const int plane[2] = {planes.AddPlane(normals[0]), planes.AddPlane(normals[1])};
    for (std::size_t k = 0; k < normal_rows; ++k) {
      ASSERT_TRUE(planes.AddRow(rows[k].a, rows[k].r, rows[k].depth));
      planes.AddTangentPoint(plane[patch_of[k]], rows[k].r, rows[k].depth);
    }
    grouped.Begin();
    const int group[2] = {grouped.AddGroup(normals[0]), grouped.AddGroup(normals[1])};
    const int grouped_plane[2] = {grouped.AddPlane(normals[0]), grouped.AddPlane(normals[1])};
    for (std::size_t k = 0; k < normal_rows; ++k) {
      ASSERT_TRUE(grouped.AddGroupRow(group[patch_of[k]], rows[k].r, rows[k].depth));
      grouped.AddTangentPoint(grouped_plane[patch_of[k]], rows[k].r, rows[k].depth);
    }
    const Vec3 f(u(rng), u(rng), 3.0 + u(rng));
    const Vec3 tau = Vec3(0.03 + 0.03 * u(rng), 0.02 * u(rng), 0.02).cross(f);
    ASSERT_TRUE(explicit_rows.Solve(f, tau).converged) << "trial " << trial;
    ASSERT_TRUE(planes.Solve(f, tau).converged) << "trial " << trial;
    ASSERT_TRUE(grouped.Solve(f, tau).converged) << "trial " << trial;
    double scale = 0.0;
    for (std::size_t k = 0; k < normal_rows; ++k) scale = std::max(scale, explicit_rows.lambda(k));
    for (std::size_t k = 0; k < normal_rows; ++k) {
      EXPECT_NEAR(planes.lambda(k), explicit_rows.lambda(k), 1e-9 * scale) << "trial " << trial;
      EXPECT_NEAR(grouped.lambda(k), explicit_rows.lambda(k), 1e-9 * scale) << "trial " << trial;
      EXPECT_EQ(grouped.direction(k), rows[k].a);
    }
    Vec3 total_f = Vec3::Zero(), total_tau = Vec3::Zero();
    for (int patch = 0; patch < 2; ++patch) {
      Vec3 want_f = Vec3::Zero(), want_m = Vec3::Zero(), got_f, got_m;
      for (std::size_t j = normal_rows; j < rows.size(); ++j) {
        if (patch_of[(j - normal_rows) / 2] != patch) continue;
        want_f += explicit_rows.lambda(j) * rows[j].a;
        want_m += explicit_rows.lambda(j) * rows[j].r.cross(rows[j].a);
      }
      planes.PlaneWrench(plane[patch], &got_f, &got_m);
      EXPECT_LT((got_f - want_f).norm(), 1e-9 * f.norm()) << "trial " << trial;
      EXPECT_LT((got_m - want_m).norm(), 1e-10 * f.norm()) << "trial " << trial;
      EXPECT_NEAR(got_f.dot(normals[patch]), 0.0, 1e-12 * f.norm());
      total_f += got_f;
      total_tau += got_m;
    }
    for (std::size_t k = 0; k < normal_rows; ++k) {
      total_f += planes.lambda(k) * rows[k].a;
      total_tau += planes.lambda(k) * rows[k].r.cross(rows[k].a);
    }
    EXPECT_LT((total_f - f).norm(), 1e-6) << "trial " << trial;
    EXPECT_LT((total_tau - tau).norm(), 1e-7) << "trial " << trial;
  }
  EXPECT_EQ(planes.AddPlane(Vec3::UnitZ()), -1);  // capacity 2
  EXPECT_EQ(grouped.AddGroup(Vec3::UnitZ()), -1);
  EXPECT_FALSE(grouped.AddGroupRow(5, Vec3::Zero(), 1e-3));
}

// Successive ticks: the warm start gives the cold start's answer in fewer passes.
TEST(PressureSplit, AWarmStartGivesTheColdAnswerInFewerPasses) {
  const auto points = Patch(10, 0.05, 0.0, 1e-3);
  PressureSplit warm(points.size()), cold(points.size());
  int warm_passes = 0, cold_passes = 0;
  for (int tick = 0; tick < 100; ++tick) {
    const double s = 0.01 * tick;
    const Vec3 f(0, 0, 2.0 + 0.2 * std::sin(s)), tau(0.05 * std::cos(s), 0.06 * std::sin(s), 0);
    Load(points, &warm);
    Load(points, &cold);
    cold.Reset();
    const auto w = warm.Solve(f, tau);
    const auto c = cold.Solve(f, tau);
    ASSERT_TRUE(w.converged && c.converged);
    if (tick > 0) {
      warm_passes += w.passes;
      cold_passes += c.passes;
    }
    for (std::size_t k = 0; k < points.size(); ++k) {
      ASSERT_NEAR(warm.lambda(k), cold.lambda(k), 1e-10) << "tick " << tick << " row " << k;
    }
  }
  // The moments lift part of the patch, so a cold start takes Newton steps; the warm start
  // begins on (or next to) the right piece.
  EXPECT_LT(warm_passes, cold_passes);
  std::printf("passes over 99 ticks: warm %d, cold %d\n", warm_passes, cold_passes);
}

// What the patch cannot carry (a torque about its normal, with normal rows only) is left out,
// and the force is still carried; nothing becomes NaN.
TEST(PressureSplit, AnUncarryableTorqueIsLeftOutAndTheForceCarried) {
  const auto points = Patch(5, 0.04, 0.0, 1e-3);
  PressureSplit split(points.size());
  Load(points, &split);
  const Vec3 f(0, 0, 2.0), tau(0, 0, 0.3);
  (void)split.Solve(f, tau);
  const Carried c = CarriedBy(points, split);
  EXPECT_LT((c.f - f).norm(), 1e-6);
  EXPECT_NEAR(c.tau.z(), 0.0, 1e-12);
  for (std::size_t k = 0; k < points.size(); ++k) EXPECT_TRUE(std::isfinite(split.lambda(k)));
}

TEST(PressureSplit, SolveDoesNotAllocate) {
  const auto points = Patch(20, 0.05, 0.0, 1e-3);
  PressureSplit split(points.size());
  mrh::testing::AllocGuard guard;
  for (int tick = 0; tick < 10; ++tick) {
    Load(points, &split);
    (void)split.Solve(Vec3(0, 0, 1.0 + tick), Vec3(0.01 * tick, 0, 0));
  }
  EXPECT_EQ(guard.count(), 0);
}

TEST(PressureSplit, ZeroCapacityIsRefused) {
  EXPECT_THAT(
      [] {
        PressureSplit split(0);
      },
      ::testing::ThrowsMessage<InvalidArgument>(::testing::HasSubstr("capacity = 0")));
}

}  // namespace
}  // namespace mrh::render
