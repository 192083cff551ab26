// SPDX-License-Identifier: Apache-2.0
// Builds FCL 0.7 geometries from shapes and runs its signed-distance query (libccd GJK/EPA).
#include "geometry/fcl_query.h"

#include <fcl/fcl.h>

#include <cmath>
#include <exception>
#include <utility>
#include <vector>

#include "mrh/core/assert.h"

namespace mrh::geometry::internal {

struct FclGeometry {
  std::unique_ptr<fcl::CollisionGeometryd> geometry;
};

namespace {

std::unique_ptr<fcl::CollisionGeometryd> MakeConvex(const ConvexMesh& mesh, double scale) {
  auto vertices = std::make_shared<std::vector<fcl::Vector3d>>();
  vertices->reserve(mesh.vertices.size());
  for (const Vec3& v : mesh.vertices) vertices->push_back(scale * v);
  // FCL's face list: for each face, its vertex count followed by its vertex indices.
  auto faces = std::make_shared<std::vector<int>>();
  faces->reserve(4 * mesh.triangles.size());
  for (const std::array<int, 3>& t : mesh.triangles) {
    faces->push_back(3);
    faces->insert(faces->end(), t.begin(), t.end());
  }
  return std::make_unique<fcl::Convexd>(std::move(vertices),
                                        static_cast<int>(mesh.triangles.size()), std::move(faces));
}

}  // namespace

std::shared_ptr<const FclGeometry> MakeFclGeometry(const Shape& shape, double scale, bool core) {
  MRH_DEMAND(scale > 0.0);
  const Vec3 size = scale * shape.size;
  auto out = std::make_shared<FclGeometry>();
  switch (shape.type) {
    case ShapeType::kSphere:
      out->geometry = std::make_unique<fcl::Sphered>(core ? 0.0 : size.x());
      break;
    case ShapeType::kCapsule:  // FCL takes the full length of the cylinder part
      out->geometry = std::make_unique<fcl::Capsuled>(core ? 0.0 : size.x(), 2.0 * size.y());
      break;
    case ShapeType::kCylinder:  // FCL takes the full height
      out->geometry = std::make_unique<fcl::Cylinderd>(size.x(), 2.0 * size.y());
      break;
    case ShapeType::kEllipsoid:
      out->geometry = std::make_unique<fcl::Ellipsoidd>(size.x(), size.y(), size.z());
      break;
    case ShapeType::kBox:  // FCL takes full side lengths
      out->geometry = std::make_unique<fcl::Boxd>(2.0 * size.x(), 2.0 * size.y(), 2.0 * size.z());
      break;
    case ShapeType::kMesh:
      MRH_DEMAND(shape.mesh != nullptr);
      out->geometry = MakeConvex(*shape.mesh, scale);
      break;
    case ShapeType::kPlane:
      MRH_DEMAND(shape.type != ShapeType::kPlane);
      break;
  }
  return out;
}

std::optional<FclDistance> FclQuery(const FclGeometry& a, const FclGeometry& b, const Pose& X_AB,
                                    double tolerance, bool signed_distance) {
  fcl::DistanceRequestd request;
  request.enable_signed_distance = signed_distance;
  request.enable_nearest_points = true;
  // GST_INDEP aborts on Convex in distance() (DEPENDENCIES.md); libccd's GJK/EPA is exact on
  // polytopes.
  request.gjk_solver_type = fcl::GST_LIBCCD;
  request.distance_tolerance = tolerance;
  fcl::Transform3d X_b = fcl::Transform3d::Identity();
  X_b.linear() = X_AB.q.toRotationMatrix();
  X_b.translation() = X_AB.p;
  fcl::DistanceResultd result;
  try {
    fcl::distance(a.geometry.get(), fcl::Transform3d::Identity(), b.geometry.get(), X_b, request,
                  result);
  } catch (const std::exception&) {
    return std::nullopt;
  }
  // Measured on FCL 0.7 (tests/geometry): nearest_points[0] lies on the first geometry and [1] on
  // the second, both in the query frame, for separated and penetrating pairs alike.
  const FclDistance out{result.min_distance, result.nearest_points[0], result.nearest_points[1]};
  // GJK has returned NaN witness points for a point exactly on a mesh vertex.
  if (!std::isfinite(out.distance) || !out.p_A.allFinite() || !out.p_B.allFinite()) {
    return std::nullopt;
  }
  return out;
}

}  // namespace mrh::geometry::internal
