// SPDX-License-Identifier: Apache-2.0
// Penetration region of two convex polyhedra (Muller–Preparata via qhull_r) and the plane +
// contact-point description of a contact (thesis §3.2.1).
#pragma once

#include <optional>
#include <span>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/geometry/distance.h"
#include "mrh/geometry/polyhedron.h"

namespace mrh::geometry {

/// Tolerances of the region analysis (m).
struct RegionOptions {
  /// A region vertex within this of the plane is "on the plane" and is not a contact point
  /// (Springhead: 5e-8 m).
  double on_plane_tolerance = 5e-8;
  /// A halfspace closer than this to the interior point means zero volume (touching contact).
  double touching_tolerance = 1e-9;
};

/// How a pair's contact points were obtained.
enum class RegionStatus {
  kSeparated,  ///< distance > 0: fallback, the pointer-side closest point
  kTouching,   ///< zero-volume overlap: fallback
  kRegion,     ///< penetration-region vertices below the plane
  kFailed,     ///< region analysis failed (qhull error): fallback
};

/// Plane + contact points of one pointer/object pair, world frame (thesis §3.2.1).
struct ContactRegion {
  RegionStatus status = RegionStatus::kSeparated;
  double distance = 0.0;       ///< signed distance (m), < 0 penetrating
  Vec3 n_W = Vec3::UnitZ();    ///< unit plane normal, object → pointer
  Vec3 c_W = Vec3::Zero();     ///< plane point: the object-side witness point
  std::vector<Vec3> points_W;  ///< contact points (region vertices below the plane, or the
                               ///< pointer-side closest point in a fallback)
  std::vector<double> depths;  ///< n·(c − p) per point (m); >= 0 below the plane
};

/// Vertices of the intersection of halfspaces (one frame) around `interior`, which must lie
/// strictly inside all of them: qhull_r halfspace intersection (the dual convex hull).
/// Returns nullopt when the intersection has no volume or qhull fails; never prints, never
/// aborts. Not RT-safe (allocates).
std::optional<std::vector<Vec3>> IntersectHalfspaces(std::span<const Halfspace> halfspaces,
                                                     const Vec3& interior);

/// Plane and contact points of `pointer` at X_WP against `object` at X_WO, from their signed
/// distance `d` (A = pointer, B = object, as returned by SignedDistance). The normal is the
/// witness direction (object → pointer); for penetration the region is intersected with
/// qhull_r around the witness midpoint, or around the centre of the region's largest inscribed
/// ball when the midpoint is not well inside it (EPA witnesses of an edge–edge contact, or
/// the inscribed polyhedra of curved shapes). Not RT-safe.
ContactRegion ComputeContactRegion(const ConvexPolyhedron& pointer, const Pose& X_WP,
                                   const ConvexPolyhedron& object, const Pose& X_WO,
                                   const DistanceResult& d, const RegionOptions& options = {});

}  // namespace mrh::geometry
