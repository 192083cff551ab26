// SPDX-License-Identifier: Apache-2.0
// Tests of the analytic plane (half-space) distance against closed-form answers.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <limits>

#include "distance_test_util.h"
#include "mrh/core/error.h"
#include "mrh/geometry/distance.h"

namespace mrh::geometry {
namespace {

using testing::At;
using testing::BoxMeshShape;
using testing::BoxShape;
using testing::CapsuleShape;
using testing::GenericRotation;
using testing::IsNear;
using testing::PlaneShape;
using testing::SphereShape;

// Closed form on ~1 m shapes: roundoff only.
constexpr double kTol = 1e-12;

// A tilted floor through (0.5, -1, 0.2); its normal is the third column of its rotation.
Pose TiltedFloor() {
  return Pose{Vec3(0.5, -1.0, 0.2), Quat(Eigen::AngleAxisd(0.3, Vec3(1, 1, 0).normalized()))};
}

TEST(PlaneDistanceTest, SphereAboveTiltedPlaneIsHeightMinusRadius) {
  const CollisionShape plane(PlaneShape());
  const CollisionShape sphere(SphereShape(0.25));
  const Pose X_WP = TiltedFloor();
  const Vec3 n = X_WP.q * Vec3::UnitZ();
  const Vec3 centre = X_WP * Vec3(0.3, -0.4, 0.75);
  const DistanceResult r = SignedDistance(plane, X_WP, sphere, Pose{centre, GenericRotation()});
  EXPECT_NEAR(r.distance, 0.5, kTol);
  EXPECT_THAT(r.p_WA, IsNear(Vec3(centre - 0.75 * n), kTol));
  EXPECT_THAT(r.p_WB, IsNear(Vec3(centre - 0.25 * n), kTol));
}

TEST(PlaneDistanceTest, SphereSunkInPlaneAsFirstOrSecondShape) {
  const CollisionShape plane(PlaneShape());
  const CollisionShape sphere(SphereShape(0.25));
  const Pose X_WP = TiltedFloor();
  const Vec3 n = X_WP.q * Vec3::UnitZ();
  const Vec3 centre = X_WP * Vec3(0.3, -0.4, 0.1);
  const DistanceResult r =
      SignedDistance(sphere, At(centre.x(), centre.y(), centre.z()), plane, X_WP);
  EXPECT_NEAR(r.distance, -0.15, kTol);
  EXPECT_THAT(r.p_WA, IsNear(Vec3(centre - 0.25 * n), kTol));  // sphere's deepest point
  EXPECT_THAT(r.p_WB, IsNear(Vec3(centre - 0.1 * n), kTol));   // its projection on the plane
}

TEST(PlaneDistanceTest, RotatedBoxTouchesWithItsLowestCorner) {
  const CollisionShape plane(PlaneShape());
  const CollisionShape box(BoxShape(0.4, 0.3, 0.2));
  const Pose X_WP = TiltedFloor();
  const Vec3 n = X_WP.q * Vec3::UnitZ();
  const Pose X_WB{X_WP * Vec3(0.1, 0.2, 0.15), GenericRotation()};
  // Enumerate the corners: the one lowest along n sets the distance.
  double expected = std::numeric_limits<double>::infinity();
  Vec3 lowest = Vec3::Zero();
  for (int i = 0; i < 8; ++i) {
    const Vec3 corner =
        X_WB * Vec3((i & 1) ? 0.4 : -0.4, (i & 2) ? 0.3 : -0.3, (i & 4) ? 0.2 : -0.2);
    const double height = n.dot(corner - X_WP.p);
    if (height < expected) {
      expected = height;
      lowest = corner;
    }
  }
  ASSERT_LT(expected, 0.0);  // the case is meant to penetrate
  const DistanceResult r = SignedDistance(plane, X_WP, box, X_WB);
  EXPECT_NEAR(r.distance, expected, kTol);
  EXPECT_THAT(r.p_WB, IsNear(lowest, kTol));
  EXPECT_THAT(r.p_WA, IsNear(Vec3(lowest - expected * n), kTol));
}

TEST(PlaneDistanceTest, FlatBoxAndCubeMeshBothReportBottomFaceCentre) {
  const CollisionShape plane(PlaneShape());
  const CollisionShape box(BoxShape(1, 1, 1));
  const CollisionShape mesh(BoxMeshShape(1, 1, 1));
  const Pose X_WP = TiltedFloor();
  const Pose X_WB{X_WP * Vec3(0.3, 0.2, 1.5), X_WP.q};  // resting flat, 0.5 above the plane
  for (const CollisionShape* shape : {&box, &mesh}) {
    const DistanceResult r = SignedDistance(plane, X_WP, *shape, X_WB);
    EXPECT_NEAR(r.distance, 0.5, kTol);
    EXPECT_THAT(r.p_WB, IsNear(X_WB * Vec3(0, 0, -1), kTol));
  }
}

TEST(PlaneDistanceTest, TiltedCapsuleTouchesWithItsLowerCap) {
  const CollisionShape plane(PlaneShape());
  const CollisionShape capsule(CapsuleShape(0.1, 0.5));
  // Capsule axis tilted 60 degrees from the vertical: its lower cap centre is 0.25 below its
  // centre.
  const Quat tilt(Eigen::AngleAxisd(M_PI / 3.0, Vec3::UnitX()));
  const DistanceResult r = SignedDistance(capsule, At(0.2, 0.3, 0.3, tilt), plane, At(0, 0, 0));
  EXPECT_NEAR(r.distance, 0.3 - 0.25 - 0.1, kTol);
  const Vec3 lower_cap = Vec3(0.2, 0.3, 0.3) + tilt * Vec3(0, 0, -0.5);
  EXPECT_THAT(r.p_WA, IsNear(Vec3(lower_cap - Vec3(0, 0, 0.1)), kTol));
  EXPECT_THAT(r.p_WB, IsNear(Vec3(lower_cap.x(), lower_cap.y(), 0.0), kTol));
}

TEST(PlaneDistanceTest, TwoPlanesAreRejected) {
  const CollisionShape a(PlaneShape());
  const CollisionShape b(PlaneShape());
  EXPECT_THAT(
      [&] {
        SignedDistance(a, At(0, 0, 0), b, At(0, 0, 1));
      },
      ::testing::ThrowsMessage<InvalidArgument>(
          ::testing::HasSubstr("both shapes are planes; expected at most one plane")));
}

}  // namespace
}  // namespace mrh::geometry
