// SPDX-License-Identifier: Apache-2.0
// Convex polyhedra from shapes: boxes and meshes exactly, curved shapes as inscribed hulls.
#include "mrh/geometry/polyhedron.h"

#include <algorithm>
#include <cmath>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include "geometry/curved_tessellation.h"
#include "geometry/mesh_faces.h"
#include "geometry/qhull_halfspaces.h"
#include "geometry/shape_validation.h"
#include "mrh/core/error.h"

namespace mrh::geometry {
namespace {

// Fewer segments than a hexagon would approximate a sphere by less than half its volume.
constexpr int kMinCurvedSegments = 6;
using Parts = internal::PolyhedronParts;

void ValidateSegments(int curved_segments, const char* where) {
  if (curved_segments < kMinCurvedSegments) {
    throw InvalidArgument(std::string(where) +
                          ": curved_segments = " + std::to_string(curved_segments) +
                          "; expected an integer >= 6 (raise rendering.curved_segments)");
  }
}

Parts BoxParts(const Vec3& half) {
  Parts parts;
  for (int i = 0; i < 8; ++i) {
    parts.vertices.emplace_back((i & 1) ? half.x() : -half.x(), (i & 2) ? half.y() : -half.y(),
                                (i & 4) ? half.z() : -half.z());
  }
  for (int axis = 0; axis < 3; ++axis) {
    for (const double sign : {1.0, -1.0}) {
      parts.faces.push_back(Halfspace{sign * Vec3::Unit(axis), half[axis]});
    }
  }
  return parts;
}

std::optional<Parts> HullParts(std::span<const Vec3> points) {
  const std::optional<ConvexMesh> hull = internal::ConvexHullMesh(points);
  if (!hull) return std::nullopt;
  return internal::MergeCoplanarTriangles(*hull);
}

}  // namespace

ConvexPolyhedron ConvexPolyhedron::FromShape(const Shape& shape, int curved_segments) {
  ValidateSegments(curved_segments, "ConvexPolyhedron::FromShape");
  internal::ValidateShape(shape);
  std::optional<Parts> parts;
  switch (shape.type) {
    case ShapeType::kPlane:
      parts = Parts{{}, {Halfspace{Vec3::UnitZ(), 0.0}}};
      break;
    case ShapeType::kBox:
      parts = BoxParts(shape.size);
      break;
    case ShapeType::kMesh:
      parts = internal::MergeCoplanarTriangles(*shape.mesh);
      // Not convex or inward wound: collide with its convex hull, as MuJoCo does.
      if (!parts) parts = HullParts(shape.mesh->vertices);
      break;
    case ShapeType::kSphere:
    case ShapeType::kCapsule:
    case ShapeType::kCylinder:
    case ShapeType::kEllipsoid:
      parts = HullParts(internal::CurvedShapePoints(shape, curved_segments));
      break;
  }
  if (!parts) {
    throw InvalidArgument(std::string("ConvexPolyhedron::FromShape: the ") +
                          ShapeTypeName(shape.type) +
                          " spans no volume; expected a solid (fix the geom size or mesh)");
  }
  ConvexPolyhedron polyhedron;
  polyhedron.vertices_ = std::move(parts->vertices);
  polyhedron.faces_ = std::move(parts->faces);
  return polyhedron;
}

ConvexPolyhedron ConvexPolyhedron::FromPoints(std::span<const Vec3> points) {
  std::optional<Parts> parts = HullParts(points);
  if (!parts) {
    throw InvalidArgument("ConvexPolyhedron::FromPoints: " + std::to_string(points.size()) +
                          " points span no volume; expected at least 4 finite points, not all "
                          "in one plane");
  }
  ConvexPolyhedron polyhedron;
  polyhedron.vertices_ = std::move(parts->vertices);
  polyhedron.faces_ = std::move(parts->faces);
  return polyhedron;
}

double ConvexPolyhedron::ApproximationError(const Shape& shape, int curved_segments) {
  ValidateSegments(curved_segments, "ConvexPolyhedron::ApproximationError");
  internal::ValidateShape(shape);
  return internal::CurvedApproximationError(shape, curved_segments);
}

}  // namespace mrh::geometry
