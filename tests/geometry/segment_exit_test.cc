// SPDX-License-Identifier: Apache-2.0
// Tests of the separating-axis exit of a point or segment from a polytope.
#include "geometry/segment_exit.h"

#include <gtest/gtest.h>

#include <cmath>

#include "distance_test_util.h"

namespace mrh::geometry::internal {
namespace {

using testing::BoxMeshShape;
using testing::BoxShape;
using testing::IsNear;

constexpr double kTol = 1e-12;

TEST(ExitSegmentTest, PointInBoxLeavesThroughNearestFace) {
  const Shape box = BoxShape(1, 1, 1);
  const SegmentExit exit =
      ExitSegment(box, MakePolytopeFeatures(box), Vec3(0.6, 0.1, 0.2), Vec3::Zero());
  EXPECT_NEAR(exit.depth, 0.4, kTol);
  EXPECT_THAT(exit.u, IsNear(Vec3::UnitX(), kTol));
}

TEST(ExitSegmentTest, PointOutsideHasNegativeDepth) {
  const Shape box = BoxShape(1, 1, 1);
  const SegmentExit exit =
      ExitSegment(box, MakePolytopeFeatures(box), Vec3(0, 0, 1.5), Vec3::Zero());
  EXPECT_NEAR(exit.depth, -0.5, kTol);
  EXPECT_THAT(exit.u, IsNear(Vec3::UnitZ(), kTol));
}

TEST(ExitSegmentTest, VerticalSegmentLeavesSidewaysWhenShorterThanDepth) {
  const Shape box = BoxShape(1, 1, 1);
  // A segment from z = 0.2 to 1.8 through the top face, 0.3 from the x = +1 face.
  const SegmentExit exit =
      ExitSegment(box, MakePolytopeFeatures(box), Vec3(0.7, 0, 1.0), Vec3(0, 0, 0.8));
  EXPECT_NEAR(exit.depth, 0.3, kTol);
  EXPECT_THAT(exit.u, IsNear(Vec3::UnitX(), kTol));
}

TEST(ExitSegmentTest, DiagonalSegmentAcrossAnEdgeLeavesAlongEdgeNormal) {
  const Shape box = BoxShape(1, 1, 1);
  // A segment parallel to y crossing the edge x = z = 1, 0.1 inside along the edge's diagonal.
  const double inset = 0.1 / std::sqrt(2.0);
  const SegmentExit exit =
      ExitSegment(box, MakePolytopeFeatures(box), Vec3(1 - inset, 0, 1 - inset), Vec3(0, 5, 0));
  // The edge is parallel to the segment, so only the faces count: 0.1 / sqrt(2) each.
  EXPECT_NEAR(exit.depth, inset, kTol);
  EXPECT_TRUE(exit.u.isApprox(Vec3::UnitX(), kTol) || exit.u.isApprox(Vec3::UnitZ(), kTol));
}

TEST(ExitSegmentTest, SkewSegmentNearEdgeUsesEdgeCrossAxis) {
  const Shape box = BoxShape(1, 1, 1);
  // A segment along (1, 0, -1), 0.05 below the edge x = z = 1 and across it: the axis
  // (1, 0, 1) / sqrt(2), the cross of the edge with the segment, needs 0.05, each face
  // 0.05 sqrt(2).
  const Vec3 centre = Vec3(1, 0, 1) - 0.05 * Vec3(1, 0, 1).normalized();
  const SegmentExit exit =
      ExitSegment(box, MakePolytopeFeatures(box), centre, 0.05 * Vec3(1, 0, -1).normalized());
  EXPECT_NEAR(exit.depth, 0.05, kTol);
  EXPECT_THAT(exit.u, IsNear(Vec3(1, 0, 1).normalized(), kTol));
}

TEST(ExitSegmentTest, CubeMeshMatchesBox) {
  const Shape box = BoxShape(1, 2, 3);
  const Shape mesh = BoxMeshShape(1, 2, 3);
  const Vec3 centre(0.3, -1.2, 2.1);
  const Vec3 half(0.2, 0.5, -0.4);
  const SegmentExit a = ExitSegment(box, MakePolytopeFeatures(box), centre, half);
  const SegmentExit b = ExitSegment(mesh, MakePolytopeFeatures(mesh), centre, half);
  EXPECT_NEAR(a.depth, b.depth, kTol);
  EXPECT_THAT(a.u, IsNear(b.u, kTol));
}

}  // namespace
}  // namespace mrh::geometry::internal
