// SPDX-License-Identifier: Apache-2.0
// Private: the vertices of the intersection of two convex polyhedra (qhull_r), shared by the
// geometric IR's contact region and the contact-volume penalty (B2).
#pragma once

#include <optional>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/geometry/distance.h"
#include "mrh/geometry/polyhedron.h"

namespace mrh::geometry::internal {

/// Vertices (world, m) of A ∩ B for A at X_WA (bounded) and B at X_WB (may be a plane), from
/// their signed distance `d` (A first): the Muller–Preparata dual transform centred on the
/// witness midpoint or the intersection's Chebyshev centre (as ComputeContactRegion does).
/// nullopt when they do not penetrate by more than `touching_tolerance`, when the intersection
/// has no volume, or when qhull fails. Never prints. Not RT-safe.
std::optional<std::vector<Vec3>> RegionVertices(const ConvexPolyhedron& a, const Pose& X_WA,
                                                const ConvexPolyhedron& b, const Pose& X_WB,
                                                const DistanceResult& d, double touching_tolerance);

}  // namespace mrh::geometry::internal
