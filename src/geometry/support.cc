// SPDX-License-Identifier: Apache-2.0
// Support functions of the convex shapes, used by the analytic plane distance.
#include "geometry/support.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "mrh/core/assert.h"

namespace mrh::geometry::internal {
namespace {

// Sign of a direction component, with components below the tie tolerance counted as zero so that
// a face (or cap) squarely facing the direction yields its centre.
double TieSign(double component, double scale) {
  if (std::abs(component) <= kSupportTieTolerance * scale) return 0.0;
  return component > 0.0 ? 1.0 : -1.0;
}

Vec3 MeshSupport(const ConvexMesh& mesh, const Vec3& u) {
  double best = -std::numeric_limits<double>::infinity();
  double radius_squared = 0.0;
  for (const Vec3& v : mesh.vertices) {
    best = std::max(best, u.dot(v));
    radius_squared = std::max(radius_squared, v.squaredNorm());
  }
  // Average the vertices of the supporting feature: a face facing u gives its centroid of
  // vertices, matching the box's face centre for a box given as a mesh.
  const double tie = kSupportTieTolerance * u.norm() * std::sqrt(radius_squared);
  Vec3 sum = Vec3::Zero();
  int count = 0;
  for (const Vec3& v : mesh.vertices) {
    if (u.dot(v) >= best - tie) {
      sum += v;
      ++count;
    }
  }
  return sum / static_cast<double>(count);
}

}  // namespace

Vec3 SupportPoint(const Shape& shape, const Vec3& u) noexcept {
  const double norm = u.norm();
  MRH_ASSERT(norm > 0.0 && std::isfinite(norm));
  const Vec3& size = shape.size;
  switch (shape.type) {
    case ShapeType::kSphere:
      return size.x() / norm * u;
    case ShapeType::kCapsule:
      return size.x() / norm * u + Vec3(0.0, 0.0, TieSign(u.z(), norm) * size.y());
    case ShapeType::kCylinder: {
      const double radial = std::hypot(u.x(), u.y());
      const Vec3 rim = radial <= kSupportTieTolerance * norm
                           ? Vec3::Zero()
                           : Vec3(size.x() * u.x() / radial, size.x() * u.y() / radial, 0.0);
      return rim + Vec3(0.0, 0.0, TieSign(u.z(), norm) * size.y());
    }
    case ShapeType::kEllipsoid: {
      // Maximize u·x on x^T A^-2 x <= 1 (A = diag(radii)): x = A^2 u / |A u|.
      const Vec3 a_u = size.cwiseProduct(u);
      return size.cwiseProduct(a_u) / a_u.norm();
    }
    case ShapeType::kBox:
      return Vec3(TieSign(u.x(), norm) * size.x(), TieSign(u.y(), norm) * size.y(),
                  TieSign(u.z(), norm) * size.z());
    case ShapeType::kMesh:
      MRH_ASSERT(shape.mesh != nullptr && !shape.mesh->vertices.empty());
      return MeshSupport(*shape.mesh, u);
    case ShapeType::kPlane:
      break;
  }
  MRH_ASSERT(false && "a plane has no support point");
  return Vec3::Zero();
}

}  // namespace mrh::geometry::internal
