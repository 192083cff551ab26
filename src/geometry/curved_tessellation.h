// SPDX-License-Identifier: Apache-2.0
// Inscribed polyhedral approximations of the curved shapes and their analytic errors.
#pragma once

#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/geometry/shape.h"

namespace mrh::geometry::internal {

/// A latitude–longitude grid on the unit sphere. `longitudes` meridians per full turn; `bands`
/// latitude bands from pole to pole (a sphere) or from the equator to one pole (a capsule cap).
/// Every grid point lies on the sphere, so the polyhedron is inscribed.
struct SphereGrid {
  int longitudes = 0;
  int bands = 0;
  /// Smallest distance from the centre to a face plane of the unit-sphere polyhedron; the
  /// surface is at most 1 − plane_distance (per unit radius) from the polyhedron.
  double plane_distance = 1.0;
};

/// The grid with the fewest faces whose error is at most 1 − cos(π/curved_segments) of the
/// radius, i.e. no larger than that of a `curved_segments`-gon around a circle.
/// @pre curved_segments >= 6. Not RT-safe (a small search).
SphereGrid SphereGridFor(int curved_segments);

/// As SphereGridFor, for the two hemispherical caps and cylindrical side of a capsule.
SphereGrid CapsuleGridFor(int curved_segments);

/// Points on the true surface of a sphere, capsule, cylinder or ellipsoid whose convex hull is
/// its inscribed polyhedron (shape frame, m). @pre the shape is valid and curved. Not RT-safe.
std::vector<Vec3> CurvedShapePoints(const Shape& shape, int curved_segments);

/// Largest distance between the true surface and the hull of CurvedShapePoints (m): exact for
/// sphere, capsule and cylinder, an upper bound for an ellipsoid (r_max times the unit-sphere
/// error). @pre as CurvedShapePoints.
double CurvedApproximationError(const Shape& shape, int curved_segments);

}  // namespace mrh::geometry::internal
