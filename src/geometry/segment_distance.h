// SPDX-License-Identifier: Apache-2.0
// Closest points between two line segments (either may be a single point).
#pragma once

#include "mrh/core/spatial.h"

namespace mrh::geometry::internal {

/// The closest pair of points of two segments and their distance (m).
struct SegmentClosestPoints {
  Vec3 p_a = Vec3::Zero();  ///< on segment A
  Vec3 p_b = Vec3::Zero();  ///< on segment B
  double distance = 0.0;
};

/// Closest points between segments [a0, a1] and [b0, b1] (any common frame). A segment whose
/// ends coincide is a point. Parallel segments have many closest pairs: one of them is returned.
/// Ericson, Real-Time Collision Detection (2005), §5.1.9. RT-safe.
SegmentClosestPoints ClosestPointsOnSegments(const Vec3& a0, const Vec3& a1, const Vec3& b0,
                                             const Vec3& b1) noexcept;

}  // namespace mrh::geometry::internal
