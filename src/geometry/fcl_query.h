// SPDX-License-Identifier: Apache-2.0
// The FCL glue: FCL geometry of a shape and one signed-distance query (only fcl_query.cc sees FCL).
#pragma once

#include <memory>
#include <optional>

#include "mrh/core/spatial.h"
#include "mrh/geometry/shape.h"

namespace mrh::geometry::internal {

/// An FCL collision geometry. Opaque so that FCL's heavy headers compile in one file only.
struct FclGeometry;

/// FCL geometry of `shape` with every length multiplied by `scale`, in the shape frame. With
/// `core`, a sphere becomes its centre point and a capsule its axis segment (radius 0): the
/// core of a shape that is a point or segment inflated by a radius. Not RT-safe (allocates).
/// @pre the shape passed CollisionShape's validation and is not a plane; scale > 0.
std::shared_ptr<const FclGeometry> MakeFclGeometry(const Shape& shape, double scale, bool core);

/// FCL's signed distance between A (at the identity) and B (at X_AB), in A's frame.
struct FclDistance {
  double distance = 0.0;    ///< > 0 separated, < 0 penetrating
  Vec3 p_A = Vec3::Zero();  ///< on A: closest point, or A's point deepest inside B
  Vec3 p_B = Vec3::Zero();  ///< on B, likewise
};

/// Runs fcl::distance (nearest points on, libccd solver). With `signed_distance`: GJK, then EPA
/// when the shapes overlap. Without: GJK only, and overlapping shapes give distance -1 and no
/// points. `tolerance` (same length unit as the geometries) stops GJK and EPA once an iteration
/// improves less. Returns nothing where FCL fails: its EPA throws on some exactly aligned or
/// touching configurations ("The origin is outside of the polytope"), and its GJK has returned
/// NaN points. Not RT-safe (FCL allocates, and leaks its EPA polytope when it throws).
std::optional<FclDistance> FclQuery(const FclGeometry& a, const FclGeometry& b, const Pose& X_AB,
                                    double tolerance, bool signed_distance);

}  // namespace mrh::geometry::internal
