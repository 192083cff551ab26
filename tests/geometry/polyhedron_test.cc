// SPDX-License-Identifier: Apache-2.0
// Tests of convex polyhedra built from shapes and points, and of the curved-shape error bound.
#include "mrh/geometry/polyhedron.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

#include "distance_test_util.h"
#include "geometry/support.h"
#include "mrh/core/error.h"

namespace mrh::geometry {
namespace {

using testing::BoxMeshShape;
using testing::BoxShape;
using testing::CapsuleShape;
using testing::CylinderShape;
using testing::EllipsoidShape;
using testing::GenericRotation;
using ::testing::HasSubstr;
using testing::IsNear;
using testing::PlaneShape;
using testing::SphereShape;
using ::testing::ThrowsMessage;

constexpr double kPi = std::numbers::pi;
// Shapes here are ~0.1–1 m; constructions are closed form or qhull on exact points: roundoff.
constexpr double kTol = 1e-12;

// Largest violation of any face by any vertex, and the fewest faces through a vertex.
double MaxViolation(const ConvexPolyhedron& p) {
  double worst = -1.0;
  for (const Vec3& v : p.vertices()) {
    for (const Halfspace& h : p.faces()) worst = std::max(worst, h.a.dot(v) - h.b);
  }
  return worst;
}

int FewestFacesPerVertex(const ConvexPolyhedron& p, double tolerance) {
  int fewest = 1000;
  for (const Vec3& v : p.vertices()) {
    const auto on = [&](const Halfspace& h) {
      return std::abs(h.a.dot(v) - h.b) <= tolerance;
    };
    fewest =
        std::min(fewest, static_cast<int>(std::count_if(p.faces().begin(), p.faces().end(), on)));
  }
  return fewest;
}

// Gap between the true surface and the polyhedron along direction u: h_shape(u) − h_poly(u),
// the support functions. Its maximum over all unit u is their Hausdorff distance.
double SupportGap(const Shape& shape, const ConvexPolyhedron& p, const Vec3& u) {
  double poly = -1e300;
  for (const Vec3& v : p.vertices()) poly = std::max(poly, u.dot(v));
  return u.dot(internal::SupportPoint(shape, u)) - poly;
}

// Gap measured at the face normals, where an inscribed polyhedron is farthest from the surface.
double FaceNormalGap(const Shape& shape, const ConvexPolyhedron& p) {
  double gap = 0.0;
  for (const Halfspace& h : p.faces()) {
    gap = std::max(gap, h.a.dot(internal::SupportPoint(shape, h.a)) - h.b);
  }
  return gap;
}

// Gap measured along many random directions: a lower bound of the true largest gap.
double SampledGap(const Shape& shape, const ConvexPolyhedron& p) {
  std::mt19937 rng(7);
  std::normal_distribution<double> normal;
  double gap = 0.0;
  for (int i = 0; i < 500; ++i) {
    const Vec3 u = Vec3(normal(rng), normal(rng), normal(rng)).normalized();
    gap = std::max(gap, SupportGap(shape, p, u));
  }
  return gap;
}

TEST(ConvexPolyhedronTest, BoxHasItsEightCornersAndSixAxisFaces) {
  const ConvexPolyhedron box = ConvexPolyhedron::FromShape(BoxShape(0.1, 0.2, 0.3), 16);
  ASSERT_EQ(box.vertices().size(), 8u);
  ASSERT_EQ(box.faces().size(), 6u);
  for (const Halfspace& h : box.faces()) {
    Eigen::Index axis = 0;
    h.a.cwiseAbs().maxCoeff(&axis);
    EXPECT_THAT(h.a.cwiseAbs(), IsNear(Vec3::Unit(axis), kTol));
    EXPECT_NEAR(h.b, Vec3(0.1, 0.2, 0.3)[axis], kTol);
  }
  EXPECT_LE(MaxViolation(box), kTol);
  EXPECT_FALSE(box.unbounded());
}

TEST(ConvexPolyhedronTest, PlaneIsTheHalfspaceBelowItsZ) {
  const ConvexPolyhedron plane = ConvexPolyhedron::FromShape(PlaneShape(), 16);
  EXPECT_TRUE(plane.unbounded());
  ASSERT_EQ(plane.faces().size(), 1u);
  EXPECT_THAT(plane.faces()[0].a, IsNear(Vec3::UnitZ(), 0.0));
  EXPECT_EQ(plane.faces()[0].b, 0.0);
}

TEST(ConvexPolyhedronTest, BoxMeshMergesItsTwelveTrianglesIntoSixFaces) {
  const ConvexPolyhedron mesh = ConvexPolyhedron::FromShape(BoxMeshShape(0.1, 0.2, 0.3), 16);
  ASSERT_EQ(mesh.faces().size(), 6u);
  EXPECT_EQ(mesh.vertices().size(), 8u);
  for (const Halfspace& h : mesh.faces()) {
    Eigen::Index axis = 0;
    h.a.cwiseAbs().maxCoeff(&axis);
    EXPECT_THAT(h.a.cwiseAbs(), IsNear(Vec3::Unit(axis), kTol));
    EXPECT_NEAR(h.b, Vec3(0.1, 0.2, 0.3)[axis], kTol);
  }
}

TEST(ConvexPolyhedronTest, FloatRoundedRotatedMeshStillHasSixFaces) {
  // MuJoCo stores mesh vertices as float: coplanar triangles disagree by ~1e-8 m.
  Shape shape = BoxMeshShape(0.1, 0.2, 0.3);
  auto mesh = std::make_shared<ConvexMesh>(*shape.mesh);
  for (Vec3& v : mesh->vertices) v = (GenericRotation() * v).cast<float>().cast<double>();
  shape.mesh = mesh;
  const ConvexPolyhedron p = ConvexPolyhedron::FromShape(shape, 16);
  EXPECT_EQ(p.faces().size(), 6u);
  EXPECT_EQ(p.vertices().size(), 8u);
  EXPECT_LE(MaxViolation(p), kTol);
}

TEST(ConvexPolyhedronTest, InwardWoundMeshBecomesItsConvexHull) {
  Shape shape = BoxMeshShape(0.1, 0.2, 0.3);
  auto mesh = std::make_shared<ConvexMesh>(*shape.mesh);
  for (auto& t : mesh->triangles) std::swap(t[1], t[2]);
  shape.mesh = mesh;
  const ConvexPolyhedron p = ConvexPolyhedron::FromShape(shape, 16);
  ASSERT_EQ(p.faces().size(), 6u);
  for (const Halfspace& h : p.faces()) EXPECT_GT(h.b, 0.0);  // outward: origin inside
  EXPECT_EQ(p.vertices().size(), 8u);
}

TEST(ConvexPolyhedronTest, FromPointsDropsInteriorAndFacePoints) {
  std::vector<Vec3> points;
  for (int i = 0; i < 8; ++i) points.emplace_back(i & 1 ? 1 : -1, i & 2 ? 1 : -1, i & 4 ? 1 : -1);
  points.emplace_back(0, 0, 0);    // interior
  points.emplace_back(1, 0.2, 0);  // on a face
  points.emplace_back(1, 1, 0.5);  // on an edge
  const ConvexPolyhedron p = ConvexPolyhedron::FromPoints(points);
  EXPECT_EQ(p.vertices().size(), 8u);
  EXPECT_EQ(p.faces().size(), 6u);
  EXPECT_LE(MaxViolation(p), kTol);
}

TEST(ConvexPolyhedronTest, FromPointsRejectsFlatPoints) {
  const std::vector<Vec3> flat = {Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(1, 1, 0)};
  EXPECT_THAT(
      [&] {
        ConvexPolyhedron::FromPoints(flat);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("4 points span no volume")));
}

TEST(ConvexPolyhedronTest, RejectsFewerThanSixSegments) {
  EXPECT_THAT(
      [] {
        ConvexPolyhedron::FromShape(SphereShape(0.1), 4);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("curved_segments = 4; expected an integer >= 6")));
  EXPECT_THAT(
      [] {
        ConvexPolyhedron::ApproximationError(SphereShape(0.1), 5);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("curved_segments = 5")));
}

TEST(ConvexPolyhedronTest, RejectsDegenerateShape) {
  EXPECT_THAT(
      [] {
        ConvexPolyhedron::FromShape(SphereShape(0.0), 16);
      },
      ThrowsMessage<InvalidArgument>(HasSubstr("sphere radius = 0 m")));
}

TEST(ConvexPolyhedronTest, CurvedShapesHaveTheirVerticesOnTheTrueSurface) {
  const double r = 0.05;
  const double h = 0.08;
  for (int segments : {6, 7, 16, 33}) {
    const auto sphere = ConvexPolyhedron::FromShape(SphereShape(r), segments);
    for (const Vec3& v : sphere.vertices()) EXPECT_NEAR(v.norm(), r, kTol);
    const auto capsule = ConvexPolyhedron::FromShape(CapsuleShape(r, h), segments);
    for (const Vec3& v : capsule.vertices()) {
      EXPECT_NEAR((v - Vec3(0, 0, std::clamp(v.z(), -h, h))).norm(), r, kTol);
    }
    const auto cylinder = ConvexPolyhedron::FromShape(CylinderShape(r, h), segments);
    EXPECT_EQ(cylinder.vertices().size(), static_cast<std::size_t>(2 * segments));
    EXPECT_EQ(cylinder.faces().size(), static_cast<std::size_t>(segments + 2));
    for (const Vec3& v : cylinder.vertices()) {
      EXPECT_NEAR(v.head<2>().norm(), r, kTol);
      EXPECT_NEAR(std::abs(v.z()), h, kTol);
    }
    const Vec3 radii(0.03, 0.05, 0.09);
    const auto ellipsoid = ConvexPolyhedron::FromShape(EllipsoidShape(0.03, 0.05, 0.09), segments);
    for (const Vec3& v : ellipsoid.vertices()) EXPECT_NEAR(v.cwiseQuotient(radii).norm(), 1, kTol);
  }
}

TEST(ConvexPolyhedronTest, EveryVertexIsOnThreeFacesAndInsideAll) {
  for (const Shape& shape :
       {BoxShape(0.1, 0.2, 0.3), SphereShape(0.1), CapsuleShape(0.1, 0.2), CapsuleShape(0.1, 0.0),
        CylinderShape(0.1, 0.2), EllipsoidShape(0.1, 0.2, 0.3), BoxMeshShape(0.1, 0.2, 0.3)}) {
    const ConvexPolyhedron p = ConvexPolyhedron::FromShape(shape, 12);
    EXPECT_LE(MaxViolation(p), kTol) << ShapeTypeName(shape.type);
    EXPECT_GE(FewestFacesPerVertex(p, 1e-9), 3) << ShapeTypeName(shape.type);
    for (const Halfspace& h : p.faces()) EXPECT_NEAR(h.a.norm(), 1.0, kTol);
  }
}

TEST(ConvexPolyhedronTest, CylinderErrorIsTheInscribedPolygonSagitta) {
  for (int segments : {6, 16, 40}) {
    const Shape shape = CylinderShape(0.05, 0.1);
    const double error = ConvexPolyhedron::ApproximationError(shape, segments);
    EXPECT_NEAR(error, 0.05 * (1.0 - std::cos(kPi / segments)), kTol);
    const ConvexPolyhedron p = ConvexPolyhedron::FromShape(shape, segments);
    EXPECT_NEAR(FaceNormalGap(shape, p), error, kTol);
    EXPECT_LE(SampledGap(shape, p), error + kTol);
  }
}

TEST(ConvexPolyhedronTest, SphereAndCapsuleErrorsAreMeasuredGapsWithinThePolygonBound) {
  for (int segments : {6, 7, 12, 16, 25}) {
    for (const Shape& shape : {SphereShape(0.05), CapsuleShape(0.05, 0.1), CapsuleShape(0.05, 0)}) {
      const double error = ConvexPolyhedron::ApproximationError(shape, segments);
      const ConvexPolyhedron p = ConvexPolyhedron::FromShape(shape, segments);
      EXPECT_NEAR(FaceNormalGap(shape, p), error, kTol) << segments;
      EXPECT_LE(SampledGap(shape, p), error + kTol) << segments;
      EXPECT_LE(error, 0.05 * (1.0 - std::cos(kPi / segments)) + kTol) << segments;
    }
  }
}

TEST(ConvexPolyhedronTest, EllipsoidErrorBoundsTheMeasuredGap) {
  for (int segments : {6, 16}) {
    const Shape shape = EllipsoidShape(0.03, 0.05, 0.09);
    const double error = ConvexPolyhedron::ApproximationError(shape, segments);
    const ConvexPolyhedron p = ConvexPolyhedron::FromShape(shape, segments);
    EXPECT_LE(FaceNormalGap(shape, p), error + kTol);
    EXPECT_LE(SampledGap(shape, p), error + kTol);
    EXPECT_GT(FaceNormalGap(shape, p), 0.3 * error);  // the bound is not loose by orders
    EXPECT_LE(error, 0.09 * (1.0 - std::cos(kPi / segments)) + kTol);
  }
}

TEST(ConvexPolyhedronTest, ExactShapesHaveNoApproximationError) {
  EXPECT_EQ(ConvexPolyhedron::ApproximationError(BoxShape(0.1, 0.2, 0.3), 6), 0.0);
  EXPECT_EQ(ConvexPolyhedron::ApproximationError(BoxMeshShape(0.1, 0.2, 0.3), 6), 0.0);
  EXPECT_EQ(ConvexPolyhedron::ApproximationError(PlaneShape(), 6), 0.0);
}

TEST(ConvexPolyhedronTest, SphereErrorShrinksQuadraticallyWithSegments) {
  const double coarse = ConvexPolyhedron::ApproximationError(SphereShape(1.0), 16);
  const double fine = ConvexPolyhedron::ApproximationError(SphereShape(1.0), 32);
  EXPECT_NEAR(coarse / fine, 4.0, 1.0);
}

}  // namespace
}  // namespace mrh::geometry
