// SPDX-License-Identifier: Apache-2.0
// Signed distance and witness points between two convex shapes (FCL GJK/EPA underneath).
#pragma once

#include <memory>

#include "mrh/core/spatial.h"
#include "mrh/geometry/shape.h"

namespace mrh::geometry {

/// Result of a signed-distance query between shapes A and B, in the world frame.
struct DistanceResult {
  /// Signed distance (m): > 0 separated, < 0 penetrating (minus the penetration depth).
  double distance = 0.0;
  /// Witness point on A (m, world). Separated: A's closest point to B. Penetrating: A's point
  /// deepest inside B.
  Vec3 p_WA = Vec3::Zero();
  /// Witness point on B (m, world), defined like p_WA.
  Vec3 p_WB = Vec3::Zero();
};

/// A shape prepared once for repeated distance queries (owns the FCL geometry).
/// Construction is not RT-safe. Queries are not RT-safe either (FCL may allocate): they belong to
/// the physics thread.
class CollisionShape {
 public:
  /// @throws mrh::InvalidArgument for a degenerate shape (non-positive size, empty mesh).
  explicit CollisionShape(const Shape& shape);
  ~CollisionShape();
  CollisionShape(CollisionShape&&) noexcept;
  CollisionShape& operator=(CollisionShape&&) noexcept;

  const Shape& shape() const { return shape_; }

 private:
  friend DistanceResult SignedDistance(const CollisionShape&, const Pose&, const CollisionShape&,
                                       const Pose&);
  struct Impl;
  Shape shape_;
  std::unique_ptr<Impl> impl_;
};

/// Signed distance between A at pose X_WA and B at pose X_WB (both world frame). Planes, sphere
/// and capsule pairs and spheres against cylinders are closed form; a sphere or capsule against
/// a box or mesh uses the separating axis test and GJK; other pairs use FCL's GJK and EPA. With
/// boxes, meshes, spheres and capsules the result is exact to ~1e-9 of the pair's size. With a
/// cylinder or an ellipsoid, separated results are too, while a penetration depth is good to
/// ~1e-6 of the size and its witness points to ~sqrt(2e-6 R) (R: surface curvature radius).
/// At most one of A and B may be a plane. @throws mrh::InvalidArgument if both are. Not RT-safe.
DistanceResult SignedDistance(const CollisionShape& a, const Pose& X_WA, const CollisionShape& b,
                              const Pose& X_WB);

}  // namespace mrh::geometry
