// SPDX-License-Identifier: Apache-2.0
// Tests of the closed-form point-to-cylinder and point-near-ellipsoid distances.
#include "geometry/point_surface.h"

#include <gtest/gtest.h>

#include <cmath>

#include "distance_test_util.h"

namespace mrh::geometry::internal {
namespace {

using testing::IsNear;

constexpr double kTol = 1e-14;

TEST(PointToCylinderTest, OutsideBesideSideProjectsRadially) {
  const PointSurface c = PointToCylinder(0.5, 1.0, Vec3(0.6, 0.8, 0.3));
  EXPECT_NEAR(c.distance, 0.5, kTol);
  EXPECT_THAT(c.surface, IsNear(Vec3(0.3, 0.4, 0.3), kTol));
  EXPECT_THAT(c.normal, IsNear(Vec3(0.6, 0.8, 0), kTol));
}

TEST(PointToCylinderTest, OutsideBeyondRimGoesToRim) {
  const PointSurface c = PointToCylinder(0.5, 1.0, Vec3(0.8, 0, 1.4));
  EXPECT_NEAR(c.distance, 0.5, kTol);
  EXPECT_THAT(c.surface, IsNear(Vec3(0.5, 0, 1.0), kTol));
}

TEST(PointToCylinderTest, InsideNearSideExitsRadially) {
  const PointSurface c = PointToCylinder(0.5, 1.0, Vec3(0, -0.4, 0.2));
  EXPECT_NEAR(c.distance, -0.1, kTol);
  EXPECT_THAT(c.surface, IsNear(Vec3(0, -0.5, 0.2), kTol));
  EXPECT_THAT(c.normal, IsNear(Vec3(0, -1, 0), kTol));
}

TEST(PointToCylinderTest, InsideNearCapExitsAxially) {
  const PointSurface c = PointToCylinder(0.5, 1.0, Vec3(0.1, 0, -0.95));
  EXPECT_NEAR(c.distance, -0.05, kTol);
  EXPECT_THAT(c.surface, IsNear(Vec3(0.1, 0, -1.0), kTol));
  EXPECT_THAT(c.normal, IsNear(Vec3(0, 0, -1), kTol));
}

TEST(PointToCylinderTest, OnSurfaceIsAtZeroWithANormal) {
  const PointSurface c = PointToCylinder(0.5, 1.0, Vec3(0.3, 0.4, 0.0));
  EXPECT_NEAR(c.distance, 0.0, kTol);
  EXPECT_NEAR(c.normal.norm(), 1.0, kTol);
}

TEST(PointNearEllipsoidTest, PointJustOutsideTipIsAtItsGap) {
  const Vec3 radii(1.0, 0.5, 0.25);
  const std::optional<PointSurface> c = PointNearEllipsoid(radii, Vec3(1.0 + 1e-8, 0, 0), 1e-6);
  ASSERT_TRUE(c.has_value());
  // First order in the gap: error ~ gap^2 / radius.
  EXPECT_NEAR(c->distance, 1e-8, 1e-15);
  EXPECT_THAT(c->normal, IsNear(Vec3::UnitX(), kTol));
  EXPECT_THAT(c->surface, IsNear(Vec3::UnitX(), 1e-15));
}

TEST(PointNearEllipsoidTest, PointOnSurfaceHasTheSurfaceNormal) {
  const Vec3 radii(1.0, 0.5, 0.25);
  const Vec3 p(0.6, 0.4 * 0.5, std::sqrt(1.0 - 0.36 - 0.16) * 0.25);
  const std::optional<PointSurface> c = PointNearEllipsoid(radii, p, 1e-6);
  ASSERT_TRUE(c.has_value());
  EXPECT_NEAR(c->distance, 0.0, kTol);
  EXPECT_THAT(c->normal,
              IsNear(Vec3(p.cwiseQuotient(radii).cwiseQuotient(radii)).normalized(), kTol));
}

TEST(PointNearEllipsoidTest, FarPointsAreLeftToFcl) {
  EXPECT_FALSE(PointNearEllipsoid(Vec3(1.0, 0.5, 0.25), Vec3(0.5, 0, 0), 1e-6).has_value());
  EXPECT_FALSE(PointNearEllipsoid(Vec3(1.0, 0.5, 0.25), Vec3::Zero(), 1e-6).has_value());
}

}  // namespace
}  // namespace mrh::geometry::internal
