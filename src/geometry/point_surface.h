// SPDX-License-Identifier: Apache-2.0
// Closed-form signed distance from a point to a cylinder, and to an ellipsoid near its surface.
#pragma once

#include <optional>

#include "mrh/core/spatial.h"

namespace mrh::geometry::internal {

/// A point's signed distance (m) to a solid, the nearest surface point (the exit point when
/// inside) and the outward unit surface normal there, all in the solid's frame.
struct PointSurface {
  double distance = 0.0;  ///< > 0 outside, <= 0 inside (minus the depth)
  Vec3 surface = Vec3::Zero();
  Vec3 normal = Vec3::UnitZ();
};

/// Cylinder of radius r and half-height h along z, centred at the origin; point p in its frame.
/// A point on the axis exits radially along +x when the side is nearer than the caps. RT-safe.
PointSurface PointToCylinder(double r, double h, const Vec3& p) noexcept;

/// Ellipsoid with the given radii, centred at the origin. Answers only when p lies within
/// `band` (m) of the surface, to first order in the distance (error ~ band^2 / radius): FCL's GJK
/// asserts on a point exactly on an ellipsoid, and elsewhere FCL is accurate. RT-safe.
std::optional<PointSurface> PointNearEllipsoid(const Vec3& radii, const Vec3& p,
                                               double band) noexcept;

}  // namespace mrh::geometry::internal
