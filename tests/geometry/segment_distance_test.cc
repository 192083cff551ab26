// SPDX-License-Identifier: Apache-2.0
// Tests of the closest points between segments.
#include "geometry/segment_distance.h"

#include <gtest/gtest.h>

#include "distance_test_util.h"

namespace mrh::geometry::internal {
namespace {

using testing::IsNear;

constexpr double kTol = 1e-14;

TEST(ClosestPointsOnSegmentsTest, SkewSegmentsMeetAtCommonPerpendicular) {
  const SegmentClosestPoints c =
      ClosestPointsOnSegments(Vec3(-1, 0, 0), Vec3(1, 0, 0), Vec3(0.25, -1, 2), Vec3(0.25, 1, 2));
  EXPECT_NEAR(c.distance, 2.0, kTol);
  EXPECT_THAT(c.p_a, IsNear(Vec3(0.25, 0, 0), kTol));
  EXPECT_THAT(c.p_b, IsNear(Vec3(0.25, 0, 2), kTol));
}

TEST(ClosestPointsOnSegmentsTest, ClampsToEndpoints) {
  const SegmentClosestPoints c =
      ClosestPointsOnSegments(Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 1, 0), Vec3(3, 1, 0));
  EXPECT_THAT(c.p_a, IsNear(Vec3(1, 0, 0), kTol));
  EXPECT_THAT(c.p_b, IsNear(Vec3(2, 1, 0), kTol));
}

TEST(ClosestPointsOnSegmentsTest, ParallelOverlappingSegmentsGiveAPerpendicularPair) {
  const SegmentClosestPoints c =
      ClosestPointsOnSegments(Vec3(0, 0, 0), Vec3(2, 0, 0), Vec3(1, 0.5, 0), Vec3(3, 0.5, 0));
  EXPECT_NEAR(c.distance, 0.5, kTol);
  EXPECT_NEAR((c.p_b - c.p_a).x(), 0.0, kTol);
}

TEST(ClosestPointsOnSegmentsTest, PointAgainstSegmentProjects) {
  const SegmentClosestPoints c =
      ClosestPointsOnSegments(Vec3(0.5, 1, 0), Vec3(0.5, 1, 0), Vec3(0, 0, 0), Vec3(2, 0, 0));
  EXPECT_NEAR(c.distance, 1.0, kTol);
  EXPECT_THAT(c.p_b, IsNear(Vec3(0.5, 0, 0), kTol));
}

TEST(ClosestPointsOnSegmentsTest, TwoPointsAreThemselves) {
  const SegmentClosestPoints c =
      ClosestPointsOnSegments(Vec3(1, 2, 3), Vec3(1, 2, 3), Vec3(1, 2, 5), Vec3(1, 2, 5));
  EXPECT_NEAR(c.distance, 2.0, kTol);
  EXPECT_THAT(c.p_a, IsNear(Vec3(1, 2, 3), kTol));
}

}  // namespace
}  // namespace mrh::geometry::internal
