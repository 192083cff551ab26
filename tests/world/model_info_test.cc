// SPDX-License-Identifier: Apache-2.0
// Tests of the mesh geoms' description: the convex hull MuJoCo collides with, in the geom frame.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>

#include "mrh/world/world.h"
#include "world_test_util.h"

namespace mrh::world {
namespace {

using testing::kNoPointer;

// A 0.2 m cube given by its corners plus one interior point, authored away from its centre, and
// used by two geoms. MuJoCo recentres and rotates mesh vertices to the mesh's principal frame and
// moves the geom pose to compensate.
constexpr char kMeshScene[] = R"(
<mujoco>
  <asset>
    <mesh name="cube" vertex="0 0 0  0.2 0 0  0 0.2 0  0.2 0.2 0  0 0 0.2  0.2 0 0.2  0 0.2 0.2
                              0.2 0.2 0.2  0.1 0.1 0.1"/>
  </asset>
  <worldbody>
    <body name="pair" pos="0 0 1">
      <freejoint/>
      <geom name="left" type="mesh" mesh="cube"/>
      <geom name="right" type="mesh" mesh="cube" pos="0.5 0 0"/>
    </body>
  </worldbody>
</mujoco>)";

// Vertices are stored as float by MuJoCo.
constexpr double kFloatTol = 1e-6;

TEST(MeshGeomTest, GeomsOfOneMeshShareItsHull) {
  const World world = World::LoadString(kMeshScene, kNoPointer);
  const GeomInfo& left = world.geom(0);
  const GeomInfo& right = world.geom(1);
  ASSERT_EQ(left.shape.type, geometry::ShapeType::kMesh);
  ASSERT_NE(left.shape.mesh, nullptr);
  EXPECT_EQ(left.shape.mesh, right.shape.mesh);
  // The interior point is not on the hull.
  EXPECT_EQ(left.shape.mesh->vertices.size(), 8u);
  EXPECT_EQ(left.shape.mesh->triangles.size(), 12u);
}

TEST(MeshGeomTest, HullVerticesLandOnTheAuthoredCorners) {
  const World world = World::LoadString(kMeshScene, kNoPointer);
  const GeomInfo& left = world.geom(0);
  for (const Vec3& v_G : left.shape.mesh->vertices) {
    // Authored coordinates are in the body frame: every hull vertex maps to a corner of
    // [0, 0.2]^3.
    const Vec3 v_B = left.X_BG * v_G;
    for (int i = 0; i < 3; ++i) {
      EXPECT_NEAR(std::min(std::abs(v_B[i]), std::abs(v_B[i] - 0.2)), 0.0, kFloatTol) << v_B;
    }
  }
}

TEST(MeshGeomTest, HullTrianglesAreWoundOutward) {
  const World world = World::LoadString(kMeshScene, kNoPointer);
  const geometry::ConvexMesh& mesh = *world.geom(0).shape.mesh;
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : mesh.vertices) centre += v;
  centre /= static_cast<double>(mesh.vertices.size());
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    const Vec3& b = mesh.vertices[static_cast<std::size_t>(t[1])];
    const Vec3& c = mesh.vertices[static_cast<std::size_t>(t[2])];
    EXPECT_GT((b - a).cross(c - a).dot((a + b + c) / 3.0 - centre), 0.0);
  }
}

}  // namespace
}  // namespace mrh::world
