// SPDX-License-Identifier: Apache-2.0
// Exact world-frame axis-aligned bounding boxes of the convex shapes.
#include <algorithm>
#include <cmath>
#include <limits>

#include "mrh/core/assert.h"
#include "mrh/geometry/broadphase.h"

namespace mrh::geometry {
namespace {

// Half-extents of a shape centred at its frame origin, along the world axes, for rotation R
// (shape → world). Each row i of R holds the world axis e_i expressed in the shape frame.
Vec3 HalfExtents(const Shape& shape, const Mat3& R) {
  const Vec3& s = shape.size;
  const Vec3 axis_z = R.col(2).cwiseAbs();  // |e_i · z_S|
  switch (shape.type) {
    case ShapeType::kSphere:
      return Vec3::Constant(s.x());
    case ShapeType::kCapsule:
      // The segment ±h z_S swept by a ball of radius r.
      return s.y() * axis_z + Vec3::Constant(s.x());
    case ShapeType::kCylinder: {
      // A disc of radius r with unit normal z_S reaches r·sqrt(1 − (e_i·z_S)²) along e_i.
      Vec3 disc;
      for (int i = 0; i < 3; ++i)
        disc[i] = s.x() * std::sqrt(std::max(0.0, 1.0 - R(i, 2) * R(i, 2)));
      return s.y() * axis_z + disc;
    }
    case ShapeType::kEllipsoid:
      // max of e_i·x over x^T A^-2 x <= 1 is |A R^T e_i| (A = diag(radii)).
      return (R * s.asDiagonal()).rowwise().norm();
    case ShapeType::kBox:
      return R.cwiseAbs() * s;
    case ShapeType::kPlane:
    case ShapeType::kMesh:
      break;
  }
  MRH_ASSERT(false && "no closed-form extents");
  return Vec3::Zero();
}

}  // namespace

Aabb Aabb::Unbounded() noexcept {
  constexpr double kInf = std::numeric_limits<double>::infinity();
  return Aabb{Vec3::Constant(-kInf), Vec3::Constant(kInf)};
}

Aabb ComputeAabb(const Shape& shape, const Pose& X_WS) noexcept {
  if (shape.type == ShapeType::kPlane) return Aabb::Unbounded();
  const Mat3 R = X_WS.q.normalized().toRotationMatrix();
  if (shape.type == ShapeType::kMesh) {
    MRH_ASSERT(shape.mesh != nullptr && !shape.mesh->vertices.empty());
    Aabb box{Vec3::Constant(std::numeric_limits<double>::infinity()),
             Vec3::Constant(-std::numeric_limits<double>::infinity())};
    for (const Vec3& v : shape.mesh->vertices) {
      const Vec3 p_W = X_WS.p + R * v;
      box.min = box.min.cwiseMin(p_W);
      box.max = box.max.cwiseMax(p_W);
    }
    return box;
  }
  const Vec3 h = HalfExtents(shape, R);
  return Aabb{X_WS.p - h, X_WS.p + h};
}

}  // namespace mrh::geometry
