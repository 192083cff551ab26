// SPDX-License-Identifier: Apache-2.0
// Tests of the penetration region and contact points against the analytic cases of thesis
// §3.2.1 (face–face, edge–face, vertex–face).
#include "mrh/geometry/contact_region.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include "distance_test_util.h"
#include "geometry/deepest_point.h"
#include "mrh/geometry/distance.h"
#include "mrh/geometry/polyhedron.h"

namespace mrh::geometry {
namespace {

using testing::At;
using testing::BoxMeshShape;
using testing::BoxShape;
using testing::CapsuleShape;
using testing::CylinderShape;
using ::testing::DoubleNear;
using ::testing::Each;
using testing::EllipsoidShape;
using testing::GenericRotation;
using testing::IsNear;
using testing::PlaneShape;
using ::testing::SizeIs;
using testing::SphereShape;
using ::testing::UnorderedElementsAre;

// The required accuracy for depths, normals and points on 0.1 m shapes.
constexpr double kTol = 1e-9;
// Penetration depth of the analytic cases: 1 mm, well above every tolerance.
constexpr double kDelta = 1e-3;
constexpr int kSegments = 16;
const double kSqrt2 = std::sqrt(2.0);
const double kSqrt3 = std::sqrt(3.0);

// Signed distance (A = pointer, B = object) then the region of their polyhedra.
ContactRegion Analyse(const Shape& pointer, const Pose& X_WP, const Shape& object,
                      const Pose& X_WO) {
  const DistanceResult d =
      SignedDistance(CollisionShape(pointer), X_WP, CollisionShape(object), X_WO);
  return ComputeContactRegion(ConvexPolyhedron::FromShape(pointer, kSegments), X_WP,
                              ConvexPolyhedron::FromShape(object, kSegments), X_WO, d);
}

// The 0.2 m cube pointer of T3.1 (thesis §3.3.2).
Shape Cube() {
  return BoxShape(0.1, 0.1, 0.1);
}

// Rotation that points the cube corner (1, 1, 1) up.
Quat CornerUp() {
  return Quat::FromTwoVectors(Vec3(1, 1, 1), Vec3::UnitZ());
}

TEST(ContactRegionTest, CubeFaceOnFloorGivesFourBottomCornersAtDepthDelta) {
  const ContactRegion r = Analyse(Cube(), At(0.3, -0.2, 0.1 - kDelta), PlaneShape(), Pose{});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kTol));
  EXPECT_NEAR(r.distance, -kDelta, kTol);
  EXPECT_THAT(r.points_W, UnorderedElementsAre(IsNear(Vec3(0.2, -0.3, -kDelta), kTol),
                                               IsNear(Vec3(0.4, -0.3, -kDelta), kTol),
                                               IsNear(Vec3(0.2, -0.1, -kDelta), kTol),
                                               IsNear(Vec3(0.4, -0.1, -kDelta), kTol)));
  EXPECT_THAT(r.depths, Each(DoubleNear(kDelta, kTol)));
}

TEST(ContactRegionTest, CubeFaceOnTiltedFloorIsTheSameInTheFloorFrame) {
  const Pose X_WF{Vec3(0.5, -1.0, 0.2), GenericRotation()};
  const ContactRegion r = Analyse(
      Cube(), X_WF * At(0.3, -0.2, 0.1 - kDelta, Quat(Eigen::AngleAxisd(0.4, Vec3::UnitZ()))),
      PlaneShape(), X_WF);
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.n_W, IsNear(Vec3(X_WF.q * Vec3::UnitZ()), kTol));
  ASSERT_THAT(r.points_W, SizeIs(4));
  for (const Vec3& p : r.points_W) EXPECT_NEAR((X_WF.Inverse() * p).z(), -kDelta, kTol);
  EXPECT_THAT(r.depths, Each(DoubleNear(kDelta, kTol)));
}

TEST(ContactRegionTest, CubeEdgeOnFloorGivesTheTwoEdgeEndsAtDepthDelta) {
  const Quat edge_down(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()));
  const ContactRegion r =
      Analyse(Cube(), At(0.3, -0.2, 0.1 * kSqrt2 - kDelta, edge_down), PlaneShape(), Pose{});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kTol));
  EXPECT_THAT(r.points_W, UnorderedElementsAre(IsNear(Vec3(0.2, -0.2, -kDelta), kTol),
                                               IsNear(Vec3(0.4, -0.2, -kDelta), kTol)));
  EXPECT_THAT(r.depths, Each(DoubleNear(kDelta, kTol)));
}

TEST(ContactRegionTest, ObjectCornerIntoPointerFaceGivesThreePointsAtDepthDelta) {
  const Vec3 apex(0, 0, 0.1 * kSqrt3);
  const ContactRegion r =
      Analyse(Cube(), At(0, 0, apex.z() - kDelta + 0.1), Cube(), Pose{Vec3::Zero(), CornerUp()});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kTol));
  EXPECT_THAT(r.c_W, IsNear(apex, kTol));
  // The cube's three edges leave the corner at 1/sqrt(3) to the vertical: depth delta is
  // sqrt(3) delta along each.
  const auto along_edge = [&](int axis) {
    return Vec3(apex - kSqrt3 * kDelta * (CornerUp() * Vec3::Unit(axis)));
  };
  EXPECT_THAT(r.points_W,
              UnorderedElementsAre(IsNear(along_edge(0), kTol), IsNear(along_edge(1), kTol),
                                   IsNear(along_edge(2), kTol)));
  EXPECT_THAT(r.depths, Each(DoubleNear(kDelta, kTol)));
}

TEST(ContactRegionTest, CrossedEdgesGiveTheBuriedPointerEdgeEnds) {
  // Pointer edge along x at z = -delta, object edge along y at z = 0: the region is the
  // tetrahedron (±delta, 0, -delta), (0, ±delta, 0); the object edge's ends lie on the plane.
  const Quat pointer_edge_down(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()));
  const Quat object_edge_up(Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitY()));
  const ContactRegion r = Analyse(Cube(), At(0, 0, 0.1 * kSqrt2 - kDelta, pointer_edge_down),
                                  Cube(), At(0, 0, -0.1 * kSqrt2, object_edge_up));
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kTol));
  EXPECT_THAT(r.points_W, UnorderedElementsAre(IsNear(Vec3(kDelta, 0, -kDelta), kTol),
                                               IsNear(Vec3(-kDelta, 0, -kDelta), kTol)));
  EXPECT_THAT(r.depths, Each(DoubleNear(kDelta, kTol)));
}

TEST(ContactRegionTest, MeshCornerIntoPointerFaceGivesThreePoints) {
  const Vec3 apex(0, 0, 0.1 * kSqrt3);
  const ContactRegion r = Analyse(Cube(), At(0, 0, apex.z() - kDelta + 0.1),
                                  BoxMeshShape(0.1, 0.1, 0.1), Pose{Vec3::Zero(), CornerUp()});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kTol));
  EXPECT_THAT(r.points_W, SizeIs(3));
  EXPECT_THAT(r.depths, Each(DoubleNear(kDelta, kTol)));
}

TEST(ContactRegionTest, CoplanarSidesOfEqualCubesGiveFourPoints) {
  const ContactRegion r = Analyse(Cube(), At(0, 0, 0.2 - kDelta), Cube(), Pose{});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kTol));
  EXPECT_THAT(r.points_W, SizeIs(4));
  EXPECT_THAT(r.depths, Each(DoubleNear(kDelta, kTol)));
}

TEST(ContactRegionTest, SliverRegionStillGivesFourPoints) {
  const double sliver = 1e-6;  // 2e5 times thinner than wide
  const ContactRegion r = Analyse(Cube(), At(0, 0, 0.1 - sliver), PlaneShape(), Pose{});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.points_W, SizeIs(4));
  EXPECT_THAT(r.depths, Each(DoubleNear(sliver, kTol)));
}

TEST(ContactRegionTest, SeparatedPairGivesThePointerClosestPointAtNegativeDepth) {
  const double gap = 2e-3;
  const ContactRegion r = Analyse(Cube(), At(0.3, -0.2, 0.1 + gap), PlaneShape(), Pose{});
  EXPECT_EQ(r.status, RegionStatus::kSeparated);
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kTol));
  EXPECT_THAT(r.points_W, UnorderedElementsAre(IsNear(Vec3(0.3, -0.2, gap), kTol)));
  EXPECT_THAT(r.depths, Each(DoubleNear(-gap, kTol)));
}

TEST(ContactRegionTest, TouchingPairFallsBackSilently) {
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const ContactRegion r = Analyse(Cube(), At(0.3, -0.2, 0.1), PlaneShape(), Pose{});
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(r.status, RegionStatus::kTouching);
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kTol));
  EXPECT_THAT(r.points_W, SizeIs(1));
  EXPECT_THAT(r.depths, Each(DoubleNear(0.0, kTol)));
  EXPECT_EQ(out + err, "");
}

TEST(ContactRegionTest, PenetrationBelowTouchingToleranceIsTouching) {
  const ContactRegion r = Analyse(Cube(), At(0, 0, 0.1 - 1e-10), PlaneShape(), Pose{});
  EXPECT_EQ(r.status, RegionStatus::kTouching);
}

TEST(ContactRegionTest, RegionThinnerThanOnPlaneToleranceIsTouching) {
  const double thin = 2e-8;  // between touching (1e-9) and on-plane (5e-8) tolerances
  const ContactRegion r = Analyse(Cube(), At(0, 0, 0.1 - thin), PlaneShape(), Pose{});
  EXPECT_EQ(r.status, RegionStatus::kTouching);
  EXPECT_THAT(r.depths, Each(DoubleNear(thin, kTol)));
}

TEST(ContactRegionTest, SpherePoleIntoPointerFaceGivesOnePointPerPoleFace) {
  const double radius = 0.05;
  const ConvexPolyhedron sphere = ConvexPolyhedron::FromShape(SphereShape(radius), kSegments);
  int pole_faces = 0;
  for (const Halfspace& h : sphere.faces()) pole_faces += std::abs(h.a.z() * radius - h.b) < kTol;
  const ContactRegion r =
      Analyse(Cube(), At(0, 0, radius - kDelta + 0.1), SphereShape(radius), Pose{});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kTol));
  EXPECT_THAT(r.points_W, SizeIs(pole_faces));
  EXPECT_THAT(r.depths, Each(DoubleNear(kDelta, kTol)));
}

// Turns the sphere polyhedron's face nearest the centre (the largest gap) to face up.
Quat WorstFaceUp(double radius) {
  const ConvexPolyhedron sphere = ConvexPolyhedron::FromShape(SphereShape(radius), kSegments);
  Halfspace worst = sphere.faces()[0];
  for (const Halfspace& h : sphere.faces()) worst = h.b < worst.b ? h : worst;
  return Quat::FromTwoVectors(worst.a, Vec3::UnitZ());
}

TEST(ContactRegionTest, CurvedObjectFaceBelowThePlaneGivesNoContactPoints) {
  // The polyhedron's top face is the approximation error below the true top c: its vertices
  // are on the object's side and must not become contact points; the pointer's ones below
  // keep their depth from the true surface.
  const double radius = 0.05;
  const double error = ConvexPolyhedron::ApproximationError(SphereShape(radius), kSegments);
  const double depth = error + kDelta;
  const ContactRegion r = Analyse(Cube(), At(0, 0, radius - depth + 0.1), SphereShape(radius),
                                  Pose{Vec3::Zero(), WorstFaceUp(radius)});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.points_W, SizeIs(::testing::Ge(4u)));
  EXPECT_THAT(r.depths, Each(DoubleNear(depth, kTol)));
}

TEST(ContactRegionTest, ContactShallowerThanTheApproximationFallsBackToTheWitness) {
  const double radius = 0.05;
  const double depth = 0.5 * ConvexPolyhedron::ApproximationError(SphereShape(radius), kSegments);
  const ContactRegion r = Analyse(Cube(), At(0, 0, radius - depth + 0.1), SphereShape(radius),
                                  Pose{Vec3::Zero(), WorstFaceUp(radius)});
  EXPECT_EQ(r.status, RegionStatus::kTouching);
  EXPECT_THAT(r.points_W, UnorderedElementsAre(IsNear(Vec3(0, 0, radius - depth), kTol)));
  EXPECT_THAT(r.depths, Each(DoubleNear(depth, kTol)));
}

TEST(ContactRegionTest, LyingCapsuleGivesPointsAlongItsTopRidge) {
  const double radius = 0.03;
  const double half_length = 0.05;
  // Capsule axis along world x, its first meridian (a ridge of the polyhedron) up.
  const Quat lying(Eigen::AngleAxisd(-std::numbers::pi / 2, Vec3::UnitY()));
  const ContactRegion r = Analyse(Cube(), At(0, 0, radius - kDelta + 0.1),
                                  CapsuleShape(radius, half_length), Pose{Vec3::Zero(), lying});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kTol));
  EXPECT_THAT(r.points_W, SizeIs(::testing::Ge(4u)));
  EXPECT_THAT(r.depths, Each(DoubleNear(kDelta, kTol)));
  double x_min = 1.0;
  double x_max = -1.0;
  for (const Vec3& p : r.points_W) {
    x_min = std::min(x_min, p.x());
    x_max = std::max(x_max, p.x());
  }
  EXPECT_LE(x_min, -half_length);
  EXPECT_GE(x_max, half_length);
}

TEST(ContactRegionTest, UprightCylinderCapUnderPointerFaceGivesTheCapPolygonAtDepthDelta) {
  // The flat cap is exact: the region is the cap polygon, δ thick; its pointer-side face holds
  // the contact points, one per cap vertex, all δ below the cap.
  const double radius = 0.04;
  const double half_height = 0.03;
  const Shape cylinder = CylinderShape(radius, half_height);
  const ConvexPolyhedron poly = ConvexPolyhedron::FromShape(cylinder, kSegments);
  int cap_vertices = 0;
  for (const Vec3& v : poly.vertices()) cap_vertices += std::abs(v.z() - half_height) < kTol;
  ASSERT_GE(cap_vertices, 6);
  const ContactRegion r = Analyse(Cube(), At(0, 0, half_height - kDelta + 0.1), cylinder, Pose{});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kTol));
  EXPECT_THAT(r.points_W, SizeIs(cap_vertices));
  EXPECT_THAT(r.depths, Each(DoubleNear(kDelta, kTol)));
  for (const Vec3& p : r.points_W) {
    EXPECT_NEAR(p.z(), half_height - kDelta, kTol);
    EXPECT_LE(p.head<2>().norm(), radius + kTol);
  }
}

TEST(ContactRegionTest, EllipsoidPoleIntoPointerFaceGivesOnePointPerPoleFace) {
  // A flat ellipsoid's first ring of vertices lies rz(1 − cos 15°) = 0.68 mm below its pole, so
  // the pole alone enters the pointer when the depth is less than that.
  const double rz = 0.02;
  const double depth = 2e-4;
  const Shape ellipsoid = EllipsoidShape(0.05, 0.03, rz);
  const ConvexPolyhedron poly = ConvexPolyhedron::FromShape(ellipsoid, kSegments);
  int pole_faces = 0;
  for (const Halfspace& h : poly.faces()) pole_faces += std::abs(h.a.z() * rz - h.b) < kTol;
  ASSERT_GE(pole_faces, 3);
  const ContactRegion r = Analyse(Cube(), At(0, 0, rz - depth + 0.1), ellipsoid, Pose{});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  // FCL's ellipsoid is genuinely curved, so the normal is libccd's EPA direction, good to the
  // bounds documented in src/geometry/pair_distance.cc (kCurvedEpaTolerance): 1e-3 rad at worst,
  // 6e-7 measured here; the depths inherit that tilt over the ~5 mm the points spread.
  constexpr double kCurvedNormalTol = 1e-3;
  constexpr double kCurvedDepthTol = 1e-7;
  EXPECT_THAT(r.n_W, IsNear(Vec3::UnitZ(), kCurvedNormalTol));
  EXPECT_THAT(r.points_W, SizeIs(pole_faces));
  EXPECT_THAT(r.depths, Each(DoubleNear(depth, kCurvedDepthTol)));
}

TEST(ContactRegionTest, SpherePointerOnFloorGivesItsBottomPole) {
  const double radius = 0.05;
  const ContactRegion r =
      Analyse(SphereShape(radius), At(0.1, 0.2, radius - kDelta), PlaneShape(), Pose{});
  ASSERT_EQ(r.status, RegionStatus::kRegion);
  EXPECT_THAT(r.points_W, UnorderedElementsAre(IsNear(Vec3(0.1, 0.2, -kDelta), kTol)));
  EXPECT_THAT(r.depths, Each(DoubleNear(kDelta, kTol)));
}

TEST(ContactRegionTest, PlanePointerFails) {
  const ConvexPolyhedron plane = ConvexPolyhedron::FromShape(PlaneShape(), kSegments);
  const ConvexPolyhedron cube = ConvexPolyhedron::FromShape(Cube(), kSegments);
  DistanceResult d;
  d.distance = -0.01;
  d.p_WA = Vec3(0, 0, 0.09);
  d.p_WB = Vec3(0, 0, 0.1);
  const ContactRegion r = ComputeContactRegion(plane, Pose{}, cube, At(0, 0, 0.19), d);
  EXPECT_EQ(r.status, RegionStatus::kFailed);
  EXPECT_THAT(r.points_W, SizeIs(1));
}

}  // namespace
}  // namespace mrh::geometry
