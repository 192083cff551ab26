// SPDX-License-Identifier: Apache-2.0
// Pins down FCL 0.7's conventions that SignedDistance relies on: which witness point lies on
// which shape, in which frame, and what an unsigned query reports for overlapping shapes.
#include "geometry/fcl_query.h"

#include <gtest/gtest.h>

#include "distance_test_util.h"

namespace mrh::geometry::internal {
namespace {

using testing::BoxShape;
using testing::IsNear;
using testing::SphereShape;

// Unit boxes: FCL's GJK/EPA on polytopes is exact up to roundoff.
constexpr double kTol = 1e-9;
constexpr double kStop = 1e-12;

FclDistance Query(const FclGeometry& a, const FclGeometry& b, const Pose& X_AB,
                  bool signed_distance) {
  const std::optional<FclDistance> r = FclQuery(a, b, X_AB, kStop, signed_distance);
  EXPECT_TRUE(r.has_value());
  return r.value_or(FclDistance{});
}

TEST(FclQueryTest, SeparatedPointsAreOnFirstAndSecondShapeInQueryFrame) {
  const auto a = MakeFclGeometry(BoxShape(1, 1, 1), 1.0, false);
  const auto b = MakeFclGeometry(BoxShape(0.5, 0.5, 0.5), 1.0, false);
  // B turned about z keeps its bottom face parallel to A's top face.
  const Pose X_AB{Vec3(0.1, 0.2, 1.8), Quat(Eigen::AngleAxisd(0.5, Vec3::UnitZ()))};
  for (bool signed_distance : {false, true}) {
    const FclDistance r = Query(*a, *b, X_AB, signed_distance);
    EXPECT_NEAR(r.distance, 0.3, kTol);
    EXPECT_NEAR(r.p_A.z(), 1.0, kTol);  // on A's top face
    EXPECT_NEAR(r.p_B.z(), 1.3, kTol);  // on B's bottom face, expressed in the query frame
    EXPECT_THAT(Vec3(r.p_B - r.p_A), IsNear(Vec3(0, 0, 0.3), kTol));
  }
}

TEST(FclQueryTest, PenetratingPointsAreEachShapesPointDeepestInTheOther) {
  const auto a = MakeFclGeometry(BoxShape(1, 1, 1), 1.0, false);
  const auto b = MakeFclGeometry(BoxShape(0.5, 0.5, 0.5), 1.0, false);
  const FclDistance r = Query(*a, *b, Pose{Vec3(0.1, 0.2, 1.3), Quat::Identity()}, true);
  EXPECT_NEAR(r.distance, -0.2, kTol);
  EXPECT_NEAR(r.p_A.z(), 1.0, kTol);  // A's top face lies inside B
  EXPECT_NEAR(r.p_B.z(), 0.8, kTol);  // B's bottom face lies inside A
}

TEST(FclQueryTest, UnsignedQueryOnOverlapReportsMinusOne) {
  const auto a = MakeFclGeometry(BoxShape(1, 1, 1), 1.0, false);
  const auto b = MakeFclGeometry(BoxShape(0.5, 0.5, 0.5), 1.0, false);
  const FclDistance r = Query(*a, *b, Pose{Vec3(0.1, 0.2, 1.3), Quat::Identity()}, false);
  EXPECT_EQ(r.distance, -1.0);
}

TEST(FclQueryTest, ScaledGeometryScalesTheAnswer) {
  const auto a = MakeFclGeometry(BoxShape(1, 1, 1), 4.0, false);
  const auto b = MakeFclGeometry(SphereShape(0.5), 4.0, false);
  const FclDistance r = Query(*a, *b, Pose{Vec3(0, 0, 8.0), Quat::Identity()}, false);
  EXPECT_NEAR(r.distance, 2.0, kTol);
}

TEST(FclQueryTest, SphereCoreIsItsCentre) {
  const auto a = MakeFclGeometry(BoxShape(1, 1, 1), 1.0, false);
  const auto b = MakeFclGeometry(SphereShape(0.5), 1.0, true);
  const FclDistance r = Query(*a, *b, Pose{Vec3(0.2, 0.1, 1.7), Quat::Identity()}, true);
  EXPECT_NEAR(r.distance, 0.7, kTol);
  EXPECT_THAT(r.p_B, IsNear(Vec3(0.2, 0.1, 1.7), kTol));
}

}  // namespace
}  // namespace mrh::geometry::internal
