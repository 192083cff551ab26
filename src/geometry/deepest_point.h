// SPDX-License-Identifier: Apache-2.0
// The point deepest inside a set of halfspaces (Chebyshev centre), by a small simplex LP.
#pragma once

#include <optional>
#include <span>

#include "mrh/core/spatial.h"
#include "mrh/geometry/polyhedron.h"

namespace mrh::geometry::internal {

/// The centre and radius of the largest ball inside every halfspace (unit normals).
struct InscribedBall {
  Vec3 centre = Vec3::Zero();
  /// min over halfspaces of b − a·centre (m); <= 0 when the intersection is empty or flat.
  double radius = 0.0;
};

/// Maximizes s subject to a_k·y + s <= b_k by the two-phase simplex method (Bland's rule) on
/// the dual LP: min Σ λ_k (b_k − a_k·origin) subject to Σ λ_k a_k = 0, Σ λ_k = 1, λ >= 0, whose
/// tableau has only 4 rows. `origin` (any point near the halfspaces) only centres the numbers.
/// Returns nullopt when the dual is infeasible, i.e. the intersection holds balls of any
/// radius, or when the iteration cap is hit (an unbounded prism still has a finite answer).
/// Not RT-safe (allocates).
std::optional<InscribedBall> DeepestPoint(std::span<const Halfspace> halfspaces,
                                          const Vec3& origin);

}  // namespace mrh::geometry::internal
