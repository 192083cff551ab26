// SPDX-License-Identifier: Apache-2.0
// Support functions of the convex shapes (the farthest point of a shape along a direction).
#pragma once

#include "mrh/core/spatial.h"
#include "mrh/geometry/shape.h"

namespace mrh::geometry::internal {

/// Relative tolerance under which a direction component counts as zero, so that a flat feature
/// (a box face, a cylinder cap, a mesh face) facing the direction returns its centre rather than
/// an arbitrary corner. It moves the support value by at most this fraction of the shape size.
inline constexpr double kSupportTieTolerance = 1e-12;

/// Support point of `shape` along direction u_S (shape frame; need not be unit), in the shape
/// frame: a point s of the shape maximizing u_S · s. Among tied points of a flat feature the
/// feature's centre is returned (for a mesh: the mean of the tied vertices).
/// @pre shape is not a plane, u_S is finite and non-zero, the shape passed CollisionShape's
/// validation. RT-safe (a mesh is scanned vertex by vertex, O(number of vertices)).
Vec3 SupportPoint(const Shape& shape, const Vec3& u_S) noexcept;

}  // namespace mrh::geometry::internal
