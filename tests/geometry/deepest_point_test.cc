// SPDX-License-Identifier: Apache-2.0
// The contact region's half-space helpers: the deepest point of an intersection of half-spaces
// and the intersection's vertices.
#include "geometry/deepest_point.h"

#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "distance_test_util.h"
#include "mrh/geometry/contact_region.h"

namespace mrh::geometry {
namespace {

using testing::IsNear;
using ::testing::SizeIs;

const double kSqrt3 = std::sqrt(3.0);

std::vector<Halfspace> Box(const Vec3& half) {
  std::vector<Halfspace> box;
  for (int axis = 0; axis < 3; ++axis) {
    box.push_back(Halfspace{Vec3::Unit(axis), half[axis]});
    box.push_back(Halfspace{-Vec3::Unit(axis), half[axis]});
  }
  return box;
}

TEST(DeepestPointTest, BoxBallTouchesItsNarrowestFacesAtTheCentreLine) {
  std::vector<Halfspace> box = Box(Vec3(1.0, 0.5, 2.0));
  for (Halfspace& h : box) h.b += h.a.dot(Vec3(0.3, -0.2, 0.1));  // centred at (0.3, -0.2, 0.1)
  const auto ball = internal::DeepestPoint(box, Vec3(0.9, 0.2, -1.5));
  ASSERT_TRUE(ball.has_value());
  EXPECT_NEAR(ball->radius, 0.5, 1e-12);
  EXPECT_NEAR(ball->centre.y(), -0.2, 1e-12);
}

TEST(DeepestPointTest, TetrahedronBallIsItsInscribedSphere) {
  // Corner tetrahedron x, y, z >= 0, x + y + z <= 1: inradius 1 / (3 + sqrt(3)).
  std::vector<Halfspace> tetra = {{-Vec3::UnitX(), 0.0},
                                  {-Vec3::UnitY(), 0.0},
                                  {-Vec3::UnitZ(), 0.0},
                                  {Vec3::Ones().normalized(), 1 / kSqrt3}};
  const auto ball = internal::DeepestPoint(tetra, Vec3(5, -3, 2));
  ASSERT_TRUE(ball.has_value());
  const double r = 1.0 / (3.0 + kSqrt3);
  EXPECT_NEAR(ball->radius, r, 1e-12);
  EXPECT_THAT(ball->centre, IsNear(Vec3::Constant(r), 1e-12));
}

TEST(DeepestPointTest, DisjointHalfspacesGiveANegativeRadius) {
  std::vector<Halfspace> box = Box(Vec3::Ones());
  box.push_back(Halfspace{-Vec3::UnitX(), -3.0});  // x >= 3, beyond the box's x <= 1
  const auto ball = internal::DeepestPoint(box, Vec3::Zero());
  ASSERT_TRUE(ball.has_value());
  EXPECT_NEAR(ball->radius, -1.0, 1e-12);
}

TEST(DeepestPointTest, IntersectionHoldingAnyBallHasNone) {
  // All normals in one octant: the intersection holds balls of any radius.
  const std::vector<Halfspace> open = {{Vec3::UnitX(), 1.0},
                                       {Vec3::UnitY(), 1.0},
                                       {Vec3::UnitZ(), 1.0},
                                       {Vec3::Ones().normalized(), 1.0}};
  EXPECT_FALSE(internal::DeepestPoint(open, Vec3::Zero()).has_value());
}

std::vector<Halfspace> UnitCube() {
  std::vector<Halfspace> cube;
  for (int axis = 0; axis < 3; ++axis) {
    cube.push_back(Halfspace{Vec3::Unit(axis), 1.0});
    cube.push_back(Halfspace{-Vec3::Unit(axis), 1.0});
  }
  return cube;
}

TEST(IntersectHalfspacesTest, DuplicatedPlanesGiveTheCubeCorners) {
  std::vector<Halfspace> twice = UnitCube();
  for (const Halfspace& h : UnitCube()) twice.push_back(h);
  const auto vertices = IntersectHalfspaces(twice, Vec3(0.1, -0.2, 0.3));
  ASSERT_TRUE(vertices.has_value());
  EXPECT_THAT(*vertices, SizeIs(8));
  for (const Vec3& v : *vertices) EXPECT_THAT(v.cwiseAbs(), IsNear(Vec3::Ones(), 1e-12));
}

TEST(IntersectHalfspacesTest, InteriorOnAFaceHasNoRegion) {
  EXPECT_FALSE(IntersectHalfspaces(UnitCube(), Vec3(1, 0, 0)).has_value());
}

TEST(IntersectHalfspacesTest, UnboundedIntersectionHasNoRegion) {
  std::vector<Halfspace> open = UnitCube();
  open.pop_back();  // no floor
  open.push_back(Halfspace{Vec3(1, 1, 1).normalized(), 2.0});
  EXPECT_FALSE(IntersectHalfspaces(open, Vec3::Zero()).has_value());
}

TEST(IntersectHalfspacesTest, QhullErrorReturnsNothingAndPrintsNothing) {
  // Side walls only: the dual points are coplanar and qhull stops with "initial simplex is
  // flat" (QH6154), which it would print to stderr if given the chance.
  std::vector<Halfspace> walls = UnitCube();
  walls.erase(walls.begin() + 4, walls.end());
  walls.push_back(Halfspace{Vec3(1, 1, 0).normalized(), 2.0});
  ::testing::internal::CaptureStdout();
  ::testing::internal::CaptureStderr();
  const auto vertices = IntersectHalfspaces(walls, Vec3::Zero());
  const std::string out = ::testing::internal::GetCapturedStdout();
  const std::string err = ::testing::internal::GetCapturedStderr();
  EXPECT_FALSE(vertices.has_value());
  EXPECT_EQ(out + err, "");
}

}  // namespace
}  // namespace mrh::geometry
