// SPDX-License-Identifier: Apache-2.0
// Preparing a shape for distance queries: its core, radius, polytope features and FCL geometry.
#include "geometry/prepared_shape.h"

namespace mrh::geometry::internal {

PreparedShape Prepare(const Shape& shape) {
  PreparedShape p;
  p.shape = shape;
  // An ellipsoid with equal radii is a sphere, and must be treated as one: FCL's EPA never
  // terminates on a sphere centred exactly on a box corner.
  if (shape.type == ShapeType::kEllipsoid && shape.size.x() == shape.size.y() &&
      shape.size.y() == shape.size.z()) {
    p.shape.type = ShapeType::kSphere;
  }
  switch (p.shape.type) {
    case ShapeType::kPlane:
      p.core = Core::kPlane;
      return p;
    case ShapeType::kSphere:
      p.core = Core::kPoint;
      p.margin = p.shape.size.x();
      break;
    case ShapeType::kCapsule:
      p.core = Core::kSegment;
      p.margin = p.shape.size.x();
      p.half_length = p.shape.size.y();
      break;
    case ShapeType::kCylinder:
    case ShapeType::kEllipsoid:
      p.curved = true;
      break;
    case ShapeType::kBox:
      p.polytope = true;
      break;
    case ShapeType::kMesh:
      p.polytope = true;
      for (const Vec3& v : p.shape.mesh->vertices) p.centre += v;
      p.centre /= static_cast<double>(p.shape.mesh->vertices.size());
      break;
  }
  if (p.polytope) p.features = MakePolytopeFeatures(p.shape);
  p.radius = p.shape.BoundingRadius();
  p.fcl_core = MakeFclGeometry(p.shape, 1.0, /*core=*/true);
  return p;
}

}  // namespace mrh::geometry::internal
