// SPDX-License-Identifier: Apache-2.0
// Faces of a convex triangle mesh: coplanar triangles merged into one halfspace each.
#pragma once

#include <optional>
#include <vector>

#include "mrh/geometry/polyhedron.h"
#include "mrh/geometry/shape.h"

namespace mrh::geometry::internal {

/// Vertices and face halfspaces of a convex polyhedron.
struct PolyhedronParts {
  std::vector<Vec3> vertices;
  std::vector<Halfspace> faces;
};

/// Relative tolerance (of the mesh's bounding-box diagonal) within which triangles are one face.
/// MuJoCo stores mesh vertices as float (relative rounding 6e-8), so coplanar triangles of its
/// hulls disagree by ~1e-7; a merged face is off its triangles by at most this much.
inline constexpr double kCoplanarRelTol = 1e-6;

/// Merges edge-connected triangles that lie within kCoplanarRelTol of one plane into one face
/// (unit outward normal, offset at its farthest vertex) and keeps the vertices on three or more
/// faces. Returns nullopt unless the triangles form a closed surface, outward wound and convex
/// at every edge (hence convex), with at least 4 faces and 4 vertices.
/// @pre triangle indices are in range. O(triangles) expected.
/// Not RT-safe.
std::optional<PolyhedronParts> MergeCoplanarTriangles(const ConvexMesh& mesh);

}  // namespace mrh::geometry::internal
