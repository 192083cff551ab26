// SPDX-License-Identifier: Apache-2.0
// Tests of SignedDistance against closed-form answers for each pair of shape kinds.
#include "mrh/geometry/distance.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>

#include "distance_test_util.h"
#include "mrh/core/error.h"

namespace mrh::geometry {
namespace {

using testing::At;
using testing::BoxMeshShape;
using testing::BoxShape;
using testing::CapsuleShape;
using testing::CylinderShape;
using testing::EllipsoidShape;
using testing::GenericRotation;
using testing::IsNear;
using testing::SphereShape;

// Shapes here are ~1 m. Sphere and capsule pairs are closed form: roundoff only.
constexpr double kExactTol = 1e-12;
// Pairs that go through FCL on polytopes (box, mesh, sphere centre, capsule axis): GJK/EPA stop
// at 1e-9 of the pair's size; allow 10x.
constexpr double kPolytopeTol = 1e-8;
// Separated pairs with a cylinder or an ellipsoid: GJK stops at 1e-12 of the size, which puts
// witness points within ~4e-9 of the surface.
constexpr double kCurvedGjkTol = 1e-8;
// Penetrating pairs with a cylinder or an ellipsoid: EPA stops at 1e-6 of the size.
constexpr double kEpaTolerance = 1e-6;
constexpr double kCurvedDepthTol = 2 * kEpaTolerance;

// EPA's witness on a surface of curvature radius R lands within ~sqrt(2 tol R) of the true point
// (the support function is flat to second order around the optimal direction).
double CurvedEpaPointTol(double curvature_radius) {
  return std::sqrt(2.0 * kEpaTolerance * curvature_radius);
}

TEST(SphereSphereDistanceTest, SeparatedGivesGapAndSurfacePointsFacingEachOther) {
  const CollisionShape a(SphereShape(1.0));
  const CollisionShape b(SphereShape(0.5));
  const Vec3 dir = Vec3(2.0, -1.0, 2.0) / 3.0;
  const DistanceResult r =
      SignedDistance(a, At(1, 2, 3), b, Pose{Vec3(1, 2, 3) + 2.0 * dir, GenericRotation()});
  EXPECT_NEAR(r.distance, 0.5, kExactTol);
  EXPECT_THAT(r.p_WA, IsNear(Vec3(1, 2, 3) + 1.0 * dir, kExactTol));
  EXPECT_THAT(r.p_WB, IsNear(Vec3(1, 2, 3) + 1.5 * dir, kExactTol));
}

TEST(SphereSphereDistanceTest, PenetratingGivesMinusDepthAndDeepestPoints) {
  const CollisionShape a(SphereShape(1.0));
  const CollisionShape b(SphereShape(0.5));
  const Vec3 dir = Vec3(2.0, -1.0, 2.0) / 3.0;
  const DistanceResult r =
      SignedDistance(a, At(0, 0, 0), b, At(1.2 * dir.x(), 1.2 * dir.y(), 1.2 * dir.z()));
  EXPECT_NEAR(r.distance, -0.3, kExactTol);
  // A's point deepest inside B is A's surface point toward B, and vice versa.
  EXPECT_THAT(r.p_WA, IsNear(1.0 * dir, kExactTol));
  EXPECT_THAT(r.p_WB, IsNear(0.7 * dir, kExactTol));
}

TEST(SphereSphereDistanceTest, ConcentricSpheresPenetrateBySumOfRadii) {
  const CollisionShape a(SphereShape(1.0));
  const CollisionShape b(SphereShape(0.5));
  const DistanceResult r = SignedDistance(a, At(0, 0, 0), b, At(0, 0, 0));
  EXPECT_NEAR(r.distance, -1.5, kExactTol);
  EXPECT_NEAR((r.p_WA - r.p_WB).norm(), 1.5, kExactTol);
}

// A sphere of radius 0.5 against the box [-1, 1]^3, placed by a generic pose. Each case gives the
// sphere centre and the expected closest box point in box coordinates.
struct SphereBoxCase {
  const char* name;
  Vec3 centre_B;
  Vec3 box_point_B;
};

class SphereBoxDistanceTest : public ::testing::TestWithParam<SphereBoxCase> {};

TEST_P(SphereBoxDistanceTest, MatchesClosedFormInEveryRegion) {
  constexpr double kRadius = 0.5;
  const SphereBoxCase& c = GetParam();
  const Pose X_WB{Vec3(0.3, -0.2, 1.0), GenericRotation()};
  const CollisionShape sphere(SphereShape(kRadius));
  const CollisionShape box(BoxShape(1, 1, 1));
  const Vec3 offset = c.centre_B - c.box_point_B;  // box surface → centre (centre outside box)
  const double expected = offset.norm() - kRadius;
  const Vec3 sphere_point_B = c.centre_B - kRadius * offset.normalized();

  const DistanceResult r =
      SignedDistance(sphere, X_WB * Pose{c.centre_B, Quat::Identity()}, box, X_WB);

  EXPECT_NEAR(r.distance, expected, kPolytopeTol) << c.name;
  EXPECT_THAT(r.p_WA, IsNear(X_WB * sphere_point_B, kPolytopeTol)) << c.name;
  EXPECT_THAT(r.p_WB, IsNear(X_WB * c.box_point_B, kPolytopeTol)) << c.name;
}

INSTANTIATE_TEST_SUITE_P(
    Regions, SphereBoxDistanceTest,
    ::testing::Values(SphereBoxCase{"face separated", Vec3(1.7, 0.2, 0.1), Vec3(1, 0.2, 0.1)},
                      SphereBoxCase{"face penetrating", Vec3(1.3, 0.2, 0.1), Vec3(1, 0.2, 0.1)},
                      SphereBoxCase{"edge separated", Vec3(1.6, 1.3, 0.1), Vec3(1, 1, 0.1)},
                      SphereBoxCase{"edge penetrating", Vec3(1.2, 1.1, 0.1), Vec3(1, 1, 0.1)},
                      SphereBoxCase{"corner separated", Vec3(1.4, 1.4, 1.4), Vec3(1, 1, 1)},
                      SphereBoxCase{"corner penetrating", Vec3(1.2, 1.2, 1.2), Vec3(1, 1, 1)}));

TEST(SphereBoxDistanceTest, CentreInsideBoxExitsThroughNearestFace) {
  const CollisionShape sphere(SphereShape(0.5));
  const CollisionShape box(BoxShape(1, 1, 1));
  const Pose X_WB{Vec3(0.3, -0.2, 1.0), GenericRotation()};
  // Nearest face is x = +1, 0.4 away: the sphere must move 0.4 + 0.5 to clear the box.
  const DistanceResult r = SignedDistance(sphere, X_WB * At(0.6, 0.1, 0.2), box, X_WB);
  EXPECT_NEAR(r.distance, -0.9, kPolytopeTol);
  EXPECT_THAT(r.p_WA, IsNear(X_WB * Vec3(0.1, 0.1, 0.2), kPolytopeTol));
  EXPECT_THAT(r.p_WB, IsNear(X_WB * Vec3(1.0, 0.1, 0.2), kPolytopeTol));
}

TEST(SphereBoxDistanceTest, CentreOnBoxFaceStillGivesDepthOfRadius) {
  // The sphere's centre touches the box, so the centre-to-box gap gives no direction.
  const CollisionShape sphere(SphereShape(0.5));
  const CollisionShape box(BoxShape(1, 1, 1));
  const DistanceResult r = SignedDistance(sphere, At(1.0, 0.2, 0.1), box, At(0, 0, 0));
  EXPECT_NEAR(r.distance, -0.5, kPolytopeTol);
  EXPECT_THAT(r.p_WA, IsNear(Vec3(0.5, 0.2, 0.1), kPolytopeTol));
  EXPECT_THAT(r.p_WB, IsNear(Vec3(1.0, 0.2, 0.1), kPolytopeTol));
}

TEST(SphereBoxDistanceTest, CentreOnBoxCornerPenetratesByRadius) {
  const CollisionShape sphere(SphereShape(0.5));
  const CollisionShape box(BoxShape(1, 1, 1));
  const DistanceResult r = SignedDistance(sphere, At(1.0, 1.0, 1.0), box, At(0, 0, 0));
  EXPECT_NEAR(r.distance, -0.5, kPolytopeTol);
  EXPECT_THAT(r.p_WB, IsNear(Vec3(1.0, 1.0, 1.0), kPolytopeTol));
  // Any direction in the corner's normal cone separates the pair by the radius.
  const Vec3 n = (r.p_WB - r.p_WA) / 0.5;
  EXPECT_NEAR(n.norm(), 1.0, kPolytopeTol);
  EXPECT_GE(n.minCoeff(), -kPolytopeTol);
}

TEST(SignedDistanceTest, SwappingShapesSwapsWitnessPoints) {
  const CollisionShape sphere(SphereShape(0.5));
  const CollisionShape box(BoxShape(1, 1, 1));
  const Pose X_WS = At(1.2, 1.1, 0.1);
  const DistanceResult ab = SignedDistance(sphere, X_WS, box, At(0, 0, 0));
  const DistanceResult ba = SignedDistance(box, At(0, 0, 0), sphere, X_WS);
  EXPECT_NEAR(ab.distance, ba.distance, kPolytopeTol);
  EXPECT_THAT(ab.p_WA, IsNear(ba.p_WB, kPolytopeTol));
  EXPECT_THAT(ab.p_WB, IsNear(ba.p_WA, kPolytopeTol));
}

TEST(BoxBoxDistanceTest, FaceOverlapGivesDepthAlongFaceNormal) {
  const CollisionShape a(BoxShape(1, 1, 1));
  const CollisionShape b(BoxShape(0.5, 0.5, 0.5));
  const DistanceResult r = SignedDistance(a, At(0, 0, 0), b, At(1.3, 0.2, 0.1));
  EXPECT_NEAR(r.distance, -0.2, kPolytopeTol);
  EXPECT_NEAR(r.p_WA.x(), 1.0, kPolytopeTol);  // A's face, deepest inside B
  EXPECT_NEAR(r.p_WB.x(), 0.8, kPolytopeTol);  // B's face, deepest inside A
  EXPECT_THAT(Vec3(r.p_WA - r.p_WB), IsNear(Vec3(0.2, 0, 0), kPolytopeTol));
  // On the overlap of the two faces (y in [-0.3, 0.7], z in [-0.4, 0.6]).
  EXPECT_GE(r.p_WA.y(), -0.3 - kPolytopeTol);
  EXPECT_LE(r.p_WA.y(), 0.7 + kPolytopeTol);
  EXPECT_GE(r.p_WA.z(), -0.4 - kPolytopeTol);
  EXPECT_LE(r.p_WA.z(), 0.6 + kPolytopeTol);
}

TEST(BoxBoxDistanceTest, RotatedBoxEdgeAboveFaceGivesEdgeGap) {
  const CollisionShape a(BoxShape(1, 1, 1));
  const CollisionShape b(BoxShape(0.5, 0.5, 0.5));
  // B turned 45 degrees about z: its vertical edge at x = 2.2 - 0.5 sqrt(2) faces A's face x = 1.
  const Quat q(Eigen::AngleAxisd(M_PI / 4.0, Vec3::UnitZ()));
  const DistanceResult r = SignedDistance(a, At(0, 0, 0), b, At(2.2, 0.0, 0.1, q));
  const double expected = 1.2 - 0.5 * std::sqrt(2.0);
  EXPECT_NEAR(r.distance, expected, kPolytopeTol);
  EXPECT_THAT(Vec3(r.p_WB - r.p_WA), IsNear(Vec3(expected, 0, 0), kPolytopeTol));
  EXPECT_NEAR(r.p_WB.y(), 0.0, kPolytopeTol);
}

TEST(CapsuleDistanceTest, SphereBesideCapsuleSideMeasuresFromAxis) {
  const CollisionShape capsule(CapsuleShape(0.2, 0.5));
  const CollisionShape sphere(SphereShape(0.3));
  const Pose X_WC{Vec3(1, 1, 1), GenericRotation()};
  const DistanceResult r = SignedDistance(capsule, X_WC, sphere, X_WC * At(0.8, 0, 0.3));
  EXPECT_NEAR(r.distance, 0.3, kExactTol);
  EXPECT_THAT(r.p_WA, IsNear(X_WC * Vec3(0.2, 0, 0.3), kExactTol));
  EXPECT_THAT(r.p_WB, IsNear(X_WC * Vec3(0.5, 0, 0.3), kExactTol));
}

TEST(CapsuleDistanceTest, CrossingCapsulesPenetrateAlongCommonNormal) {
  const CollisionShape a(CapsuleShape(0.2, 0.5));
  const CollisionShape b(CapsuleShape(0.3, 0.5));
  // B lies along x, 0.1 above A's axis along y.
  const Quat along_x(Eigen::AngleAxisd(M_PI / 2.0, Vec3::UnitY()));
  const DistanceResult r = SignedDistance(a, At(0, 0, 0), b, At(0, 0.1, 0, along_x));
  EXPECT_NEAR(r.distance, -0.4, kExactTol);
  EXPECT_THAT(r.p_WA, IsNear(Vec3(0, 0.2, 0), kExactTol));
  EXPECT_THAT(r.p_WB, IsNear(Vec3(0, -0.2, 0), kExactTol));
}

TEST(CapsuleDistanceTest, IntersectingAxesPenetrateBySumOfRadii) {
  const CollisionShape a(CapsuleShape(0.2, 0.5));
  const CollisionShape b(CapsuleShape(0.3, 0.5));
  const Quat along_x(Eigen::AngleAxisd(M_PI / 2.0, Vec3::UnitY()));
  const DistanceResult r = SignedDistance(a, At(0, 0, 0), b, At(0, 0, 0.1, along_x));
  EXPECT_NEAR(r.distance, -0.5, kExactTol);
  // The axes cross at (0, 0, 0.1); the pair separates fastest along y.
  EXPECT_NEAR(std::abs(r.p_WA.y()), 0.2, kExactTol);
  EXPECT_THAT(Vec3(r.p_WA - r.p_WB),
              IsNear(Vec3(0, 0.5 * std::copysign(1.0, r.p_WA.y()), 0), kExactTol));
}

TEST(CapsuleDistanceTest, CapsuleEndInBoxFaceGivesTipDepth) {
  const CollisionShape capsule(CapsuleShape(0.2, 0.5));
  const CollisionShape box(BoxShape(1, 1, 1));
  const Pose X_WB{Vec3(0.3, -0.2, 1.0), GenericRotation()};
  // Lower cap centre at z = 1.1: the tip reaches z = 0.9, 0.1 inside the face z = 1.
  const DistanceResult r = SignedDistance(capsule, X_WB * At(0.2, 0.1, 1.6), box, X_WB);
  EXPECT_NEAR(r.distance, -0.1, kPolytopeTol);
  EXPECT_THAT(r.p_WA, IsNear(X_WB * Vec3(0.2, 0.1, 0.9), kPolytopeTol));
  EXPECT_THAT(r.p_WB, IsNear(X_WB * Vec3(0.2, 0.1, 1.0), kPolytopeTol));
}

TEST(CylinderDistanceTest, SphereBesideCylinderSide) {
  const CollisionShape cylinder(CylinderShape(0.5, 1.0));
  const CollisionShape sphere(SphereShape(0.5));
  const Pose X_WC{Vec3(0.3, -0.2, 1.0), GenericRotation()};
  const DistanceResult r = SignedDistance(cylinder, X_WC, sphere, X_WC * At(1.2, 0, 0.4));
  EXPECT_NEAR(r.distance, 0.2, kCurvedGjkTol);
  EXPECT_THAT(r.p_WA, IsNear(X_WC * Vec3(0.5, 0, 0.4), kCurvedGjkTol));
  EXPECT_THAT(r.p_WB, IsNear(X_WC * Vec3(0.7, 0, 0.4), kCurvedGjkTol));
}

TEST(CylinderDistanceTest, CapSunkIntoBoxFace) {
  const CollisionShape cylinder(CylinderShape(0.5, 1.0));
  const CollisionShape box(BoxShape(1, 1, 1));
  const DistanceResult r = SignedDistance(cylinder, At(0.1, 0.2, 1.8), box, At(0, 0, 0));
  EXPECT_NEAR(r.distance, -0.2, kCurvedDepthTol);
  // Flat cap on a flat face: only the normal coordinate of the witnesses is determined.
  EXPECT_NEAR(r.p_WA.z(), 0.8, kCurvedDepthTol);
  EXPECT_NEAR(r.p_WB.z(), 1.0, kCurvedDepthTol);
}

TEST(CylinderDistanceTest, MillimetreCylindersDoNotTripFcl) {
  // Unscaled, FCL's EPA on millimetre-sized curved shapes fails its own assertions.
  const CollisionShape a(CylinderShape(0.003, 0.005));
  const CollisionShape b(CylinderShape(0.003, 0.005));
  const DistanceResult r = SignedDistance(a, At(0, 0, 0), b, At(0.005, 0, 0.001));
  EXPECT_NEAR(r.distance, -0.001, kCurvedDepthTol * 0.006);
}

TEST(EllipsoidDistanceTest, SphereAlongLongAxis) {
  const CollisionShape ellipsoid(EllipsoidShape(1.0, 0.5, 0.25));
  const CollisionShape sphere(SphereShape(0.3));
  const DistanceResult r = SignedDistance(ellipsoid, At(0, 0, 0), sphere, At(1.5, 0, 0));
  EXPECT_NEAR(r.distance, 0.2, kCurvedGjkTol);
  EXPECT_THAT(r.p_WA, IsNear(Vec3(1.0, 0, 0), kCurvedGjkTol));
  EXPECT_THAT(r.p_WB, IsNear(Vec3(1.2, 0, 0), kCurvedGjkTol));
}

TEST(EllipsoidDistanceTest, BoxFaceSunkIntoShortAxis) {
  const CollisionShape ellipsoid(EllipsoidShape(1.0, 0.5, 0.25));
  const CollisionShape box(BoxShape(1, 1, 1));
  const DistanceResult r = SignedDistance(ellipsoid, At(0, 0, 0), box, At(0, 0, 1.2));
  EXPECT_NEAR(r.distance, -0.05, kCurvedDepthTol);
  // The tip's curvature radius is rx^2 / rz = 4 m.
  EXPECT_THAT(r.p_WA, IsNear(Vec3(0, 0, 0.25), CurvedEpaPointTol(4.0)));
}

TEST(EllipsoidDistanceTest, RoundEllipsoidCentredOnBoxCornerBehavesAsSphere) {
  // FCL's EPA never terminates on a sphere centred exactly on a box corner; an ellipsoid with
  // equal radii is that sphere.
  const CollisionShape ellipsoid(EllipsoidShape(0.5, 0.5, 0.5));
  const CollisionShape box(BoxShape(1, 1, 1));
  const DistanceResult r = SignedDistance(ellipsoid, At(1, 1, 1), box, At(0, 0, 0));
  EXPECT_NEAR(r.distance, -0.5, kPolytopeTol);
}

TEST(MeshDistanceTest, CubeMeshAgreesWithBoxAgainstSphereEverywhere) {
  const CollisionShape box(BoxShape(1, 1, 1));
  const CollisionShape mesh(BoxMeshShape(1, 1, 1));
  const CollisionShape sphere(SphereShape(0.5));
  const Pose X_WB{Vec3(0.3, -0.2, 1.0), GenericRotation()};
  for (const Vec3& centre : {Vec3(1.7, 0.2, 0.1), Vec3(1.3, 0.2, 0.1), Vec3(1.6, 1.3, 0.1),
                             Vec3(1.2, 1.1, 0.1), Vec3(1.2, 1.2, 1.2), Vec3(0.6, 0.1, 0.2)}) {
    const Pose X_WS = X_WB * Pose{centre, Quat::Identity()};
    const DistanceResult expected = SignedDistance(sphere, X_WS, box, X_WB);
    const DistanceResult r = SignedDistance(sphere, X_WS, mesh, X_WB);
    EXPECT_NEAR(r.distance, expected.distance, kPolytopeTol) << centre.transpose();
    EXPECT_THAT(r.p_WA, IsNear(expected.p_WA, kPolytopeTol)) << centre.transpose();
    EXPECT_THAT(r.p_WB, IsNear(expected.p_WB, kPolytopeTol)) << centre.transpose();
  }
}

TEST(MeshDistanceTest, CubeMeshAgreesWithBoxAgainstRotatedBox) {
  const CollisionShape box(BoxShape(1, 1, 1));
  const CollisionShape mesh(BoxMeshShape(1, 1, 1));
  const CollisionShape other(BoxShape(0.5, 0.3, 0.2));
  for (const Pose& X_WO : {Pose{Vec3(1.9, 0.4, 0.3), GenericRotation()},
                           Pose{Vec3(1.2, 0.4, 0.3), GenericRotation()}}) {
    const DistanceResult expected = SignedDistance(box, At(0, 0, 0), other, X_WO);
    const DistanceResult r = SignedDistance(mesh, At(0, 0, 0), other, X_WO);
    EXPECT_NEAR(r.distance, expected.distance, kPolytopeTol);
  }
}

TEST(CollisionShapeTest, ZeroRadiusSphereIsRejected) {
  EXPECT_THAT(
      [] {
        CollisionShape s(SphereShape(0.0));
      },
      ::testing::ThrowsMessage<InvalidArgument>(
          ::testing::HasSubstr("sphere radius = 0 m; expected a radius > 0")));
}

TEST(CollisionShapeTest, NegativeBoxHalfExtentIsRejected) {
  EXPECT_THAT(
      [] {
        CollisionShape s(BoxShape(1.0, -0.5, 1.0));
      },
      ::testing::ThrowsMessage<InvalidArgument>(
          ::testing::HasSubstr("box half-extents = (1, -0.5, 1) m")));
}

TEST(CollisionShapeTest, NanCapsuleLengthIsRejected) {
  EXPECT_THAT(
      [] {
        CollisionShape s(CapsuleShape(0.1, std::nan("")));
      },
      ::testing::ThrowsMessage<InvalidArgument>(::testing::HasSubstr("capsule radius")));
}

TEST(CollisionShapeTest, EmptyMeshIsRejected) {
  Shape shape;
  shape.type = ShapeType::kMesh;
  shape.mesh = std::make_shared<ConvexMesh>();
  EXPECT_THAT(
      [&] {
        CollisionShape s(shape);
      },
      ::testing::ThrowsMessage<InvalidArgument>(
          ::testing::HasSubstr("mesh has 0 vertices and 0 triangles")));
}

TEST(CollisionShapeTest, MeshWithoutDataIsRejected) {
  Shape shape;
  shape.type = ShapeType::kMesh;
  EXPECT_THAT(
      [&] {
        CollisionShape s(shape);
      },
      ::testing::ThrowsMessage<InvalidArgument>(::testing::HasSubstr("mesh is null")));
}

TEST(CollisionShapeTest, MeshIndexOutOfRangeIsRejected) {
  Shape shape = BoxMeshShape(1, 1, 1);
  auto mesh = std::make_shared<ConvexMesh>(*shape.mesh);
  mesh->triangles[3][1] = 8;
  shape.mesh = mesh;
  EXPECT_THAT(
      [&] {
        CollisionShape s(shape);
      },
      ::testing::ThrowsMessage<InvalidArgument>(
          ::testing::HasSubstr("mesh triangle 3 uses vertex 8; expected indices in [0, 8)")));
}

TEST(CollisionShapeTest, MovedShapeStillAnswersQueries) {
  CollisionShape a(SphereShape(1.0));
  const CollisionShape moved(std::move(a));
  const CollisionShape b(SphereShape(1.0));
  EXPECT_NEAR(SignedDistance(moved, At(0, 0, 0), b, At(3, 0, 0)).distance, 1.0, kExactTol);
}

}  // namespace
}  // namespace mrh::geometry
