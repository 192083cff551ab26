// SPDX-License-Identifier: Apache-2.0
// Penetration of a segment (or point) into a convex polytope by the separating axis test.
#pragma once

#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/geometry/shape.h"

namespace mrh::geometry::internal {

/// Face planes and edge directions of a convex polytope (a box or a convex mesh), shape frame.
struct PolytopeFeatures {
  std::vector<Vec3> normals;    ///< unit, outward
  std::vector<double> offsets;  ///< face plane: normals[i] · x = offsets[i] (m)
  std::vector<Vec3> edges;      ///< unit edge directions
};

/// Features of a box or mesh shape. @pre the shape passed validation. Not RT-safe.
PolytopeFeatures MakePolytopeFeatures(const Shape& shape);

/// The smallest translation depth * u (u unit, shape frame) that moves the segment
/// [centre - half, centre + half] clear of the polytope; half = 0 for a point. The depth is
/// negative when the segment is already clear along u by that much.
struct SegmentExit {
  Vec3 u = Vec3::UnitZ();
  double depth = 0.0;
};

/// Separating axis test of a segment against a polytope. The candidate axes are the face
/// normals and, for a segment, the cross products of the edges with it: they include the
/// minimizing direction of the overlap. RT-safe for a box; O(faces + edges * vertices) for a mesh.
SegmentExit ExitSegment(const Shape& polytope, const PolytopeFeatures& features, const Vec3& centre,
                        const Vec3& half) noexcept;

}  // namespace mrh::geometry::internal
