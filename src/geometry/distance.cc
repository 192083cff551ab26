// SPDX-License-Identifier: Apache-2.0
// Signed distance between convex shapes: planes in closed form, other pairs through their
// prepared cores (pair_distance.cc).
#include "mrh/geometry/distance.h"

#include "geometry/prepared_shape.h"
#include "geometry/shape_validation.h"
#include "geometry/support.h"
#include "mrh/core/error.h"

namespace mrh::geometry {

struct CollisionShape::Impl {
  internal::PreparedShape prepared;
};

CollisionShape::CollisionShape(const Shape& shape)
    : shape_(shape), impl_(std::make_unique<Impl>()) {
  internal::ValidateShape(shape_);
  impl_->prepared = internal::Prepare(shape_);
}

CollisionShape::~CollisionShape() = default;
CollisionShape::CollisionShape(CollisionShape&&) noexcept = default;
CollisionShape& CollisionShape::operator=(CollisionShape&&) noexcept = default;

namespace {

using internal::Core;
using internal::PreparedShape;

// The plane (half-space z <= 0 of X_WP) against a shape: the shape's support point along the
// inward normal is its deepest (or closest) point.
DistanceResult PlaneDistance(const Pose& X_WP, const Shape& other, const Pose& X_WO,
                             bool plane_is_a) {
  const Vec3 n_W = X_WP.q * Vec3::UnitZ();
  const Vec3 s_W = X_WO * internal::SupportPoint(other, X_WO.q.conjugate() * (-n_W));
  const double distance = n_W.dot(s_W - X_WP.p);
  const Vec3 on_plane_W = s_W - distance * n_W;
  return plane_is_a ? DistanceResult{distance, on_plane_W, s_W}
                    : DistanceResult{distance, s_W, on_plane_W};
}

}  // namespace

DistanceResult SignedDistance(const CollisionShape& a, const Pose& X_WA, const CollisionShape& b,
                              const Pose& X_WB) {
  const PreparedShape& ia = a.impl_->prepared;
  const PreparedShape& ib = b.impl_->prepared;
  if (ia.core == Core::kPlane && ib.core == Core::kPlane) {
    throw InvalidArgument(
        "SignedDistance: both shapes are planes; expected at most one plane (two half-spaces "
        "have no finite signed distance): skip plane-plane pairs");
  }
  if (ia.core == Core::kPlane) return PlaneDistance(X_WA, b.shape(), X_WB, /*plane_is_a=*/true);
  if (ib.core == Core::kPlane) return PlaneDistance(X_WB, a.shape(), X_WA, /*plane_is_a=*/false);
  // Work in A's frame: FCL and the closed forms then see coordinates of the shapes' own size.
  const Pose X_AB = X_WA.Inverse() * X_WB;
  const internal::FclDistance r = internal::PairDistance(ia, ib, X_AB);
  return DistanceResult{r.distance, X_WA * r.p_A, X_WA * r.p_B};
}

}  // namespace mrh::geometry
