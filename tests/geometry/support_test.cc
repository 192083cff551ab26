// SPDX-License-Identifier: Apache-2.0
// Tests of the shapes' support functions, including the centre-of-face rule for ties.
#include "geometry/support.h"

#include <gtest/gtest.h>

#include <cmath>

#include "distance_test_util.h"

namespace mrh::geometry::internal {
namespace {

using testing::BoxMeshShape;
using testing::BoxShape;
using testing::CapsuleShape;
using testing::CylinderShape;
using testing::EllipsoidShape;
using testing::IsNear;
using testing::SphereShape;

constexpr double kTol = 1e-14;

TEST(SupportPointTest, SphereReturnsRadiusAlongDirection) {
  EXPECT_THAT(SupportPoint(SphereShape(2.0), Vec3(0, 3, 4)), IsNear(Vec3(0, 1.2, 1.6), kTol));
}

TEST(SupportPointTest, CapsulePicksCapAndCentreOnTie) {
  EXPECT_THAT(SupportPoint(CapsuleShape(0.1, 0.5), Vec3(0, 0, -2)), IsNear(Vec3(0, 0, -0.6), kTol));
  EXPECT_THAT(SupportPoint(CapsuleShape(0.1, 0.5), Vec3(3, 0, 0)), IsNear(Vec3(0.1, 0, 0), kTol));
}

TEST(SupportPointTest, CylinderPicksRimOrCapCentre) {
  const Shape cylinder = CylinderShape(0.5, 1.0);
  EXPECT_THAT(SupportPoint(cylinder, Vec3(3, 4, 1)), IsNear(Vec3(0.3, 0.4, 1.0), kTol));
  EXPECT_THAT(SupportPoint(cylinder, Vec3(0, 0, -1)), IsNear(Vec3(0, 0, -1.0), kTol));
  EXPECT_THAT(SupportPoint(cylinder, Vec3(0, 2, 0)), IsNear(Vec3(0, 0.5, 0), kTol));
}

TEST(SupportPointTest, EllipsoidPointIsOnSurfaceWithSupportValue) {
  const Shape ellipsoid = EllipsoidShape(1.0, 0.5, 0.25);
  const Vec3 u(0.3, -0.8, 0.5);
  const Vec3 s = SupportPoint(ellipsoid, u);
  EXPECT_NEAR(s.cwiseQuotient(ellipsoid.size).squaredNorm(), 1.0, kTol);
  // h(u) = |diag(radii) u| for an ellipsoid.
  EXPECT_NEAR(u.dot(s), ellipsoid.size.cwiseProduct(u).norm(), kTol);
}

TEST(SupportPointTest, BoxPicksCornerEdgeOrFaceCentre) {
  const Shape box = BoxShape(1, 2, 3);
  EXPECT_THAT(SupportPoint(box, Vec3(1, -1, 1)), IsNear(Vec3(1, -2, 3), kTol));
  EXPECT_THAT(SupportPoint(box, Vec3(0, 0, -1)), IsNear(Vec3(0, 0, -3), kTol));
  EXPECT_THAT(SupportPoint(box, Vec3(1e-17, 1, 0)), IsNear(Vec3(0, 2, 0), kTol));
}

TEST(SupportPointTest, MeshAveragesTiedVertices) {
  const Shape mesh = BoxMeshShape(1, 2, 3);
  EXPECT_THAT(SupportPoint(mesh, Vec3(1, -1, 1)), IsNear(Vec3(1, -2, 3), kTol));
  EXPECT_THAT(SupportPoint(mesh, Vec3(0, 0, -1)), IsNear(Vec3(0, 0, -3), kTol));
  EXPECT_THAT(SupportPoint(mesh, Vec3(1, 1, 0)), IsNear(Vec3(1, 2, 0), kTol));
}

}  // namespace
}  // namespace mrh::geometry::internal
