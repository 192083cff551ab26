// SPDX-License-Identifier: Apache-2.0
// Convex shape descriptions, independent of any physics engine (sizes follow MJCF conventions).
#pragma once

#include <array>
#include <memory>
#include <vector>

#include "mrh/core/spatial.h"

namespace mrh::geometry {

/// Kinds of convex primitive. A plane is the half-space z <= 0 of its own frame (MuJoCo's plane).
enum class ShapeType { kPlane, kSphere, kCapsule, kEllipsoid, kCylinder, kBox, kMesh };

/// Returns "plane", "sphere", ... RT-safe.
const char* ShapeTypeName(ShapeType type) noexcept;

/// A convex polyhedral mesh in its shape frame (m): vertices and outward-wound triangles.
struct ConvexMesh {
  std::vector<Vec3> vertices;
  std::vector<std::array<int, 3>> triangles;
};

/// A convex shape in its own frame. `size` uses MJCF semantics (m):
/// sphere {r}; capsule {r, half-length of the cylinder part along z}; cylinder {r, half-height};
/// ellipsoid {rx, ry, rz}; box {half-extents}; plane and mesh ignore it. Meshes share `mesh`.
struct Shape {
  ShapeType type = ShapeType::kSphere;
  Vec3 size = Vec3::Zero();
  std::shared_ptr<const ConvexMesh> mesh;

  /// Radius of the smallest origin-centred sphere containing the shape (m); +inf for a plane.
  double BoundingRadius() const;
};

}  // namespace mrh::geometry
