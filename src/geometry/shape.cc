// SPDX-License-Identifier: Apache-2.0
// Names and bounding radii of convex shapes.
#include "mrh/geometry/shape.h"

#include <algorithm>
#include <limits>

namespace mrh::geometry {

const char* ShapeTypeName(ShapeType type) noexcept {
  switch (type) {
    case ShapeType::kPlane:
      return "plane";
    case ShapeType::kSphere:
      return "sphere";
    case ShapeType::kCapsule:
      return "capsule";
    case ShapeType::kEllipsoid:
      return "ellipsoid";
    case ShapeType::kCylinder:
      return "cylinder";
    case ShapeType::kBox:
      return "box";
    case ShapeType::kMesh:
      return "mesh";
  }
  return "unknown";
}

double Shape::BoundingRadius() const {
  switch (type) {
    case ShapeType::kPlane:
      return std::numeric_limits<double>::infinity();
    case ShapeType::kSphere:
      return size.x();
    case ShapeType::kCapsule:
      return size.x() + size.y();
    case ShapeType::kEllipsoid:
      return size.maxCoeff();
    case ShapeType::kCylinder:
      return std::hypot(size.x(), size.y());
    case ShapeType::kBox:
      return size.norm();
    case ShapeType::kMesh: {
      double r = 0.0;
      if (mesh) {
        for (const Vec3& v : mesh->vertices) r = std::max(r, v.norm());
      }
      return r;
    }
  }
  return 0.0;
}

}  // namespace mrh::geometry
