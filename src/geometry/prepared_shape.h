// SPDX-License-Identifier: Apache-2.0
// A shape prepared for distance queries: its core (what GJK/EPA or a closed form sees), radius
// and FCL geometry.
#pragma once

#include <memory>

#include "geometry/fcl_query.h"
#include "geometry/segment_exit.h"
#include "mrh/geometry/shape.h"

namespace mrh::geometry::internal {

/// What FCL (or a closed form) sees of a shape: its core, inflated by `margin`.
enum class Core { kPlane, kPoint, kSegment, kSolid };

/// A shape prepared for queries. Spheres and capsules are a core (a point, a segment) inflated by
/// their radius; other shapes are their own core.
struct PreparedShape {
  Shape shape;
  Core core = Core::kSolid;
  double margin = 0.0;                          // sphere or capsule radius (m)
  double half_length = 0.0;                     // segment core half-length along z (m)
  bool curved = false;                          // FCL sees a curved surface (cylinder, ellipsoid)
  double radius = 0.0;                          // bounding radius of the whole shape (m)
  Vec3 centre = Vec3::Zero();                   // an interior point, shape frame (m)
  std::shared_ptr<const FclGeometry> fcl_core;  // at scale 1; null for a plane
  bool polytope = false;                        // box or mesh
  PolytopeFeatures features;                    // faces and edges of a polytope
};

/// Core, radius and FCL geometry of a validated shape. Not RT-safe.
PreparedShape Prepare(const Shape& shape);

/// Signed distance between two prepared shapes that are not planes, B at X_AB, in A's frame:
/// the cores' distance inflated by the radii, with witness points as in DistanceResult.
/// Not RT-safe.
FclDistance PairDistance(const PreparedShape& a, const PreparedShape& b, const Pose& X_AB);

}  // namespace mrh::geometry::internal
