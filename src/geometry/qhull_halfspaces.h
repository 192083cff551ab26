// SPDX-License-Identifier: Apache-2.0
// Private qhull_r helpers: the convex hull of points as an outward-wound triangle mesh.
#pragma once

#include <optional>
#include <span>

#include "mrh/core/spatial.h"
#include "mrh/geometry/shape.h"

namespace mrh::geometry::internal {

/// Convex hull of `points` (qhull_r, triangulated output "Qt"): the mesh keeps every input point
/// (unused ones are simply not referenced) and its triangles are wound counter-clockwise seen
/// from outside. Returns nullopt for fewer than 4 points, non-finite points, points that span no
/// volume, or a qhull failure. Never prints. Not RT-safe.
std::optional<ConvexMesh> ConvexHullMesh(std::span<const Vec3> points);

}  // namespace mrh::geometry::internal
