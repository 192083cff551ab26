// SPDX-License-Identifier: Apache-2.0
// Rejects degenerate shapes with a one-line message saying what to fix.
#include "geometry/shape_validation.h"

#include <cmath>
#include <string>

#include "mrh/core/error.h"
#include "mrh/core/validate.h"

namespace mrh::geometry::internal {
namespace {

bool Positive(double x) {
  return std::isfinite(x) && x > 0.0;
}

std::string Num(double x) {
  return FormatNumber(x);
}

std::string Format(const Vec3& v) {
  return '(' + Num(v.x()) + ", " + Num(v.y()) + ", " + Num(v.z()) + ')';
}

[[noreturn]] void Reject(const std::string& what, const std::string& expected) {
  throw InvalidArgument("CollisionShape: " + what + "; expected " + expected +
                        " (fix the geom size or mesh in the scene)");
}

void ValidateMesh(const Shape& shape) {
  if (!shape.mesh) Reject("mesh shape without mesh data (Shape::mesh is null)", "a convex mesh");
  const ConvexMesh& mesh = *shape.mesh;
  const std::size_t num_vertices = mesh.vertices.size();
  if (num_vertices < 4 || mesh.triangles.size() < 4) {
    Reject("mesh has " + std::to_string(num_vertices) + " vertices and " +
               std::to_string(mesh.triangles.size()) + " triangles",
           "a closed convex mesh with >= 4 vertices and >= 4 triangles");
  }
  for (std::size_t i = 0; i < num_vertices; ++i) {
    if (!mesh.vertices[i].allFinite()) {
      Reject("mesh vertex " + std::to_string(i) + " = " + Format(mesh.vertices[i]),
             "finite coordinates");
    }
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    for (int index : mesh.triangles[t]) {
      if (index < 0 || static_cast<std::size_t>(index) >= num_vertices) {
        Reject("mesh triangle " + std::to_string(t) + " uses vertex " + std::to_string(index),
               "indices in [0, " + std::to_string(num_vertices) + ")");
      }
    }
  }
}

}  // namespace

void ValidateShape(const Shape& shape) {
  const Vec3& s = shape.size;
  switch (shape.type) {
    case ShapeType::kPlane:
      return;
    case ShapeType::kSphere:
      if (!Positive(s.x())) Reject("sphere radius = " + Num(s.x()) + " m", "a radius > 0");
      return;
    case ShapeType::kCapsule:
      if (!Positive(s.x()) || !std::isfinite(s.y()) || s.y() < 0.0) {
        Reject("capsule radius = " + Num(s.x()) + " m, half-length = " + Num(s.y()) + " m",
               "radius > 0 and half-length >= 0");
      }
      return;
    case ShapeType::kCylinder:
      if (!Positive(s.x()) || !Positive(s.y())) {
        Reject("cylinder radius = " + Num(s.x()) + " m, half-height = " + Num(s.y()) + " m",
               "both > 0");
      }
      return;
    case ShapeType::kEllipsoid:
    case ShapeType::kBox:
      if (!Positive(s.x()) || !Positive(s.y()) || !Positive(s.z())) {
        Reject(std::string(ShapeTypeName(shape.type)) +
                   (shape.type == ShapeType::kBox ? " half-extents = " : " radii = ") + Format(s) +
                   " m",
               "all three > 0");
      }
      return;
    case ShapeType::kMesh:
      ValidateMesh(shape);
      return;
  }
}

}  // namespace mrh::geometry::internal
