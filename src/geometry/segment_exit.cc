// SPDX-License-Identifier: Apache-2.0
// Separating-axis penetration of a segment into a polytope: FCL's EPA aborts on points and
// segments that touch a polytope (measured on FCL 0.7), so these pairs avoid it.
#include "geometry/segment_exit.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <utility>

#include "geometry/support.h"

namespace mrh::geometry::internal {
namespace {

// Edges more nearly parallel to the segment than this (sine of the angle) give no axis.
constexpr double kParallelSine = 1e-9;

PolytopeFeatures BoxFeatures(const Vec3& half_extents) {
  PolytopeFeatures f;
  for (int axis = 0; axis < 3; ++axis) {
    const Vec3 e = Vec3::Unit(axis);
    f.normals.push_back(e);
    f.offsets.push_back(half_extents[axis]);
    f.normals.push_back(-e);
    f.offsets.push_back(half_extents[axis]);
    f.edges.push_back(e);
  }
  return f;
}

PolytopeFeatures MeshFeatures(const ConvexMesh& mesh) {
  PolytopeFeatures f;
  Vec3 centre = Vec3::Zero();
  for (const Vec3& v : mesh.vertices) centre += v;
  centre /= static_cast<double>(mesh.vertices.size());
  std::set<std::pair<int, int>> edges;
  for (const auto& t : mesh.triangles) {
    const Vec3& a = mesh.vertices[static_cast<std::size_t>(t[0])];
    Vec3 n = (mesh.vertices[static_cast<std::size_t>(t[1])] - a)
                 .cross(mesh.vertices[static_cast<std::size_t>(t[2])] - a);
    if (n.norm() > 0.0) {
      // Orient outward whatever the winding: the centroid of the vertices is inside.
      n.normalize();
      if (n.dot(a - centre) < 0.0) n = -n;
      f.normals.push_back(n);
      f.offsets.push_back(n.dot(a));
    }
    for (int k = 0; k < 3; ++k) edges.insert(std::minmax(t[k], t[(k + 1) % 3]));
  }
  for (const auto& [i, j] : edges) {
    const Vec3 d =
        mesh.vertices[static_cast<std::size_t>(j)] - mesh.vertices[static_cast<std::size_t>(i)];
    if (d.norm() > 0.0) f.edges.push_back(d.normalized());
  }
  return f;
}

}  // namespace

PolytopeFeatures MakePolytopeFeatures(const Shape& shape) {
  return shape.type == ShapeType::kBox ? BoxFeatures(shape.size) : MeshFeatures(*shape.mesh);
}

SegmentExit ExitSegment(const Shape& polytope, const PolytopeFeatures& features, const Vec3& centre,
                        const Vec3& half) noexcept {
  // Overlap along u: how far the segment must move along u to clear the polytope.
  const auto overlap = [&](const Vec3& u, double support) {
    return support - (u.dot(centre) - std::abs(u.dot(half)));
  };
  SegmentExit best;
  best.depth = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < features.normals.size(); ++i) {
    const double depth = overlap(features.normals[i], features.offsets[i]);
    if (depth < best.depth) best = SegmentExit{features.normals[i], depth};
  }
  const double length = half.norm();
  if (length == 0.0) return best;
  for (const Vec3& edge : features.edges) {
    Vec3 u = edge.cross(half);
    if (u.norm() <= kParallelSine * length) continue;
    u.normalize();
    for (const Vec3& axis : {u, Vec3(-u)}) {
      const double depth = overlap(axis, axis.dot(SupportPoint(polytope, axis)));
      if (depth < best.depth) best = SegmentExit{axis, depth};
    }
  }
  return best;
}

}  // namespace mrh::geometry::internal
