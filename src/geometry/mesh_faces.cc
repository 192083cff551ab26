// SPDX-License-Identifier: Apache-2.0
// Groups a convex mesh's coplanar triangles into faces by flooding across shared edges.
#include "geometry/mesh_faces.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numeric>
#include <unordered_map>

namespace mrh::geometry::internal {
namespace {

// A triangle whose doubled area is below this fraction of the squared mesh size has no normal.
constexpr double kDegenerateAreaRelTol = 1e-14;

using Triangle = std::array<int, 3>;

std::uint64_t EdgeKey(int i, int j) {
  const auto lo = static_cast<std::uint64_t>(std::min(i, j));
  const auto hi = static_cast<std::uint64_t>(std::max(i, j));
  return (lo << 32) | hi;
}

class FaceGrouping {
 public:
  FaceGrouping(const ConvexMesh& mesh, double scale, double tolerance)
      : mesh_(mesh), tolerance_(tolerance), group_(mesh.triangles.size(), -1) {
    for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
      normals_.push_back(Normal(mesh.triangles[t]));
      const Triangle& tri = mesh.triangles[t];
      for (int k = 0; k < 3; ++k) edges_[EdgeKey(tri[k], tri[(k + 1) % 3])].push_back(t);
    }
    min_area_ = kDegenerateAreaRelTol * scale * scale;
  }

  // Seeds a face at each not yet grouped triangle, largest first (its plane is the most
  // accurate), and floods it across shared edges to triangles within tolerance of the seed's
  // plane. Comparing with the seed, not the neighbour, keeps a finely tessellated curved
  // surface from merging into one drifting face.
  void Run() {
    std::vector<std::size_t> order(mesh_.triangles.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(), [this](std::size_t x, std::size_t y) {
      return normals_[x].norm() > normals_[y].norm();
    });
    for (std::size_t seed : order) {
      if (group_[seed] >= 0 || normals_[seed].norm() <= min_area_) continue;
      const Vec3 a = normals_[seed].normalized();
      Flood(seed, a, a.dot(Vertex(mesh_.triangles[seed][0])), static_cast<int>(seeds_.size()));
      seeds_.push_back(seed);
    }
  }

  // A closed mesh (every edge shared by exactly two triangles) is convex and outward wound iff
  // at every edge between two faces each triangle lies inside the other's halfspace.
  bool LocallyConvex(const std::vector<Halfspace>& faces) const {
    for (const auto& [key, triangles] : edges_) {
      if (triangles.size() != 2) return false;
      const int g0 = group_[triangles[0]];
      const int g1 = group_[triangles[1]];
      if (g0 < 0 || g1 < 0 || g0 == g1) continue;
      if (!Inside(triangles[1], faces[static_cast<std::size_t>(g0)]) ||
          !Inside(triangles[0], faces[static_cast<std::size_t>(g1)])) {
        return false;
      }
    }
    return true;
  }

  int num_groups() const { return static_cast<int>(seeds_.size()); }

  int group(std::size_t t) const { return group_[t]; }

  const Vec3& normal(std::size_t t) const { return normals_[t]; }

 private:
  const Vec3& Vertex(int i) const { return mesh_.vertices[static_cast<std::size_t>(i)]; }

  Vec3 Normal(const Triangle& t) const {
    return (Vertex(t[1]) - Vertex(t[0])).cross(Vertex(t[2]) - Vertex(t[0]));
  }

  bool Fits(std::size_t t, const Vec3& a, double b) const {
    // A degenerate triangle has no orientation to check and joins any face it lies in.
    if (normals_[t].norm() > min_area_ && a.dot(normals_[t]) <= 0.0) return false;
    const Triangle& tri = mesh_.triangles[t];
    return std::all_of(tri.begin(), tri.end(), [&](int i) {
      return std::abs(a.dot(Vertex(i)) - b) <= tolerance_;
    });
  }

  bool Inside(std::size_t t, const Halfspace& h) const {
    const Triangle& tri = mesh_.triangles[t];
    return std::all_of(tri.begin(), tri.end(), [&](int i) {
      return h.a.dot(Vertex(i)) <= h.b + tolerance_;
    });
  }

  void Flood(std::size_t seed, const Vec3& a, double b, int id) {
    std::vector<std::size_t> stack{seed};
    group_[seed] = id;
    while (!stack.empty()) {
      const Triangle tri = mesh_.triangles[stack.back()];
      stack.pop_back();
      for (int k = 0; k < 3; ++k) {
        for (std::size_t u : edges_.at(EdgeKey(tri[k], tri[(k + 1) % 3]))) {
          if (group_[u] < 0 && Fits(u, a, b)) {
            group_[u] = id;
            stack.push_back(u);
          }
        }
      }
    }
  }

  const ConvexMesh& mesh_;
  double tolerance_;
  double min_area_ = 0.0;
  std::vector<Vec3> normals_;  // doubled-area normals
  std::vector<int> group_;
  std::vector<std::size_t> seeds_;
  std::unordered_map<std::uint64_t, std::vector<std::size_t>> edges_;
};

// One halfspace per face: the area-weighted mean normal, offset at the face's farthest vertex.
std::vector<Halfspace> FaceHalfspaces(const ConvexMesh& mesh, const FaceGrouping& grouping) {
  const auto num_groups = static_cast<std::size_t>(grouping.num_groups());
  std::vector<Vec3> sums(num_groups, Vec3::Zero());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int g = grouping.group(t);
    if (g >= 0) sums[static_cast<std::size_t>(g)] += grouping.normal(t);
  }
  std::vector<Halfspace> faces;
  for (const Vec3& sum : sums) {
    faces.push_back(Halfspace{sum.normalized(), -std::numeric_limits<double>::infinity()});
  }
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int g = grouping.group(t);
    if (g < 0) continue;
    Halfspace& h = faces[static_cast<std::size_t>(g)];
    for (int i : mesh.triangles[t]) {
      h.b = std::max(h.b, h.a.dot(mesh.vertices[static_cast<std::size_t>(i)]));
    }
  }
  return faces;
}

// Vertices of the polyhedron: mesh vertices where three or more faces meet (a vertex inside a
// face or an edge touches fewer), each position once.
std::vector<Vec3> CornerVertices(const ConvexMesh& mesh, const FaceGrouping& grouping) {
  std::vector<std::vector<int>> faces_at(mesh.vertices.size());
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    const int g = grouping.group(t);
    if (g < 0) continue;
    for (int i : mesh.triangles[t]) {
      std::vector<int>& at = faces_at[static_cast<std::size_t>(i)];
      if (std::find(at.begin(), at.end(), g) == at.end()) at.push_back(g);
    }
  }
  std::vector<Vec3> corners;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (faces_at[i].size() >= 3) corners.push_back(mesh.vertices[i]);
  }
  const auto less = [](const Vec3& x, const Vec3& y) {
    return std::lexicographical_compare(x.data(), x.data() + 3, y.data(), y.data() + 3);
  };
  std::sort(corners.begin(), corners.end(), less);
  corners.erase(std::unique(corners.begin(), corners.end()), corners.end());
  return corners;
}

}  // namespace

std::optional<PolyhedronParts> MergeCoplanarTriangles(const ConvexMesh& mesh) {
  std::vector<bool> is_used(mesh.vertices.size(), false);
  for (const Triangle& t : mesh.triangles) {
    for (int i : t) is_used[static_cast<std::size_t>(i)] = true;
  }
  Eigen::AlignedBox3d box;
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    if (is_used[i]) box.extend(mesh.vertices[i]);
  }
  if (std::count(is_used.begin(), is_used.end(), true) < 4) return std::nullopt;
  const double scale = box.diagonal().norm();
  const double tolerance = kCoplanarRelTol * scale;
  FaceGrouping grouping(mesh, scale, tolerance);
  grouping.Run();
  std::vector<Halfspace> faces = FaceHalfspaces(mesh, grouping);
  if (!grouping.LocallyConvex(faces)) return std::nullopt;
  PolyhedronParts parts{CornerVertices(mesh, grouping), std::move(faces)};
  if (parts.faces.size() < 4 || parts.vertices.size() < 4) return std::nullopt;
  return parts;
}

}  // namespace mrh::geometry::internal
