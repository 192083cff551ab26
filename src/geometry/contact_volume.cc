// SPDX-License-Identifier: Apache-2.0
// Intersection polyhedron of a convex pair and the pressure integrals of B2 (Hasegawa & Sato
// 2004, thesis ref. [1]; see include/mrh/geometry/contact_volume.h).
#include "mrh/geometry/contact_volume.h"

#include <algorithm>
#include <cmath>

#include "geometry/qhull_halfspaces.h"
#include "geometry/region_vertices.h"
#include "mrh/core/assert.h"

namespace mrh::geometry {
namespace {

// A triangle lies on a face of A or B when its centroid is within this distance of the face's
// plane, relative to the intersection's extent (qhull's vertices are exact to ~1e-12 of it) ...
constexpr double kOnFaceRelTol = 1e-7;
// ... and its unit normal is this close to the face's outward normal (cos of ~0.08°).
constexpr double kOnFaceCos = 1.0 - 1e-6;

Vec3 AreaVector(const IntersectionVolume& v, const std::array<int, 3>& t) {
  const Vec3& p0 = v.vertices_W[static_cast<std::size_t>(t[0])];
  return (v.vertices_W[static_cast<std::size_t>(t[1])] - p0)
      .cross(v.vertices_W[static_cast<std::size_t>(t[2])] - p0);
}

// True when the triangle (centroid m, area vector s) lies on one of the faces of `shape`.
bool OnSurface(const ConvexPolyhedron& shape, const Pose& X_WS, const Vec3& m, const Vec3& s,
               double tolerance) {
  const Vec3 unit = s.normalized();
  for (const Halfspace& h : shape.faces()) {
    const Vec3 a_W = X_WS.q * h.a;
    const double b_W = h.b + a_W.dot(X_WS.p);
    if (std::abs(b_W - a_W.dot(m)) <= tolerance && a_W.dot(unit) >= kOnFaceCos) return true;
  }
  return false;
}

// n = Σ S_B − Σ S_A over the triangles on exactly one of the two surfaces (a triangle on both
// is a shared coplanar wall, which no pressure crosses). B's outward normals point into A.
Vec3 ContactNormal(const IntersectionVolume& v, const ConvexPolyhedron& a, const Pose& X_WA,
                   const ConvexPolyhedron& b, const Pose& X_WB, double extent) {
  const double tolerance = kOnFaceRelTol * extent;
  Vec3 sum = Vec3::Zero();
  for (const std::array<int, 3>& t : v.triangles) {
    const Vec3 s = AreaVector(v, t);
    if (!(s.norm() > 0.0)) continue;
    const Vec3 m = (v.vertices_W[static_cast<std::size_t>(t[0])] +
                    v.vertices_W[static_cast<std::size_t>(t[1])] +
                    v.vertices_W[static_cast<std::size_t>(t[2])]) /
                   3.0;
    const bool on_a = OnSurface(a, X_WA, m, s, tolerance);
    const bool on_b = OnSurface(b, X_WB, m, s, tolerance);
    if (on_b && !on_a) sum += s;
    if (on_a && !on_b) sum -= s;
  }
  return sum;
}

void Measure(IntersectionVolume* v) {
  double volume = 0.0;
  double shadow = 0.0;
  for (const std::array<int, 3>& t : v->triangles) {
    const Vec3 p0 = v->vertices_W[static_cast<std::size_t>(t[0])] - v->c_W;
    const Vec3 p1 = v->vertices_W[static_cast<std::size_t>(t[1])] - v->c_W;
    const Vec3 p2 = v->vertices_W[static_cast<std::size_t>(t[2])] - v->c_W;
    volume += p0.dot(p1.cross(p2)) / 6.0;
    shadow += std::abs((p1 - p0).cross(p2 - p0).dot(v->n_W));
  }
  v->volume = volume;
  v->projected_area = shadow / 4.0;
}

}  // namespace

std::optional<IntersectionVolume> IntersectConvex(const ConvexPolyhedron& a, const Pose& X_WA,
                                                  const ConvexPolyhedron& b, const Pose& X_WB,
                                                  const DistanceResult& d,
                                                  double touching_tolerance) {
  const std::optional<std::vector<Vec3>> vertices =
      internal::RegionVertices(a, X_WA, b, X_WB, d, touching_tolerance);
  if (!vertices) return std::nullopt;
  std::optional<ConvexMesh> hull = internal::ConvexHullMesh(*vertices);
  if (!hull || hull->triangles.empty()) return std::nullopt;
  IntersectionVolume v;
  v.vertices_W = std::move(hull->vertices);
  v.triangles = std::move(hull->triangles);
  Vec3 c = Vec3::Zero();
  for (const Vec3& p : v.vertices_W) c += p;
  v.c_W = c / static_cast<double>(v.vertices_W.size());
  double extent = 0.0;
  for (const Vec3& p : v.vertices_W) extent = std::max(extent, (p - v.c_W).norm());
  const Vec3 n = ContactNormal(v, a, X_WA, b, X_WB, extent);
  const Vec3 witness = d.p_WB - d.p_WA;  // B → A for a penetrating pair
  if (n.norm() > 0.0) {
    v.n_W = n.normalized();
  } else if (witness.norm() > 0.0) {
    v.n_W = witness.normalized();
  } else {
    return std::nullopt;
  }
  Measure(&v);
  if (!(v.volume > 0.0) || !(v.projected_area > 0.0)) return std::nullopt;
  return v;
}

Wrench IntegratePressure(const IntersectionVolume& v, std::span<const double> pressure,
                         PressureSurface surface) {
  MRH_ASSERT(pressure.size() == v.vertices_W.size());
  const Vec3& n = v.n_W;
  Wrench w;
  for (const std::array<int, 3>& t : v.triangles) {
    std::array<Vec3, 3> q;  // vertices relative to c, projected on the contact plane
    std::array<double, 3> f{};
    for (int i = 0; i < 3; ++i) {
      const auto k = static_cast<std::size_t>(t[static_cast<std::size_t>(i)]);
      const Vec3 p = v.vertices_W[k] - v.c_W;
      q[static_cast<std::size_t>(i)] = p - p.dot(n) * n;
      f[static_cast<std::size_t>(i)] = pressure[k];
    }
    const Vec3 s = (q[1] - q[0]).cross(q[2] - q[0]);
    if (surface == PressureSurface::kUpper && !(s.dot(n) > 0.0)) continue;
    w.f += (f[0] + f[1] + f[2]) / 6.0 * s;
    // Σ_ab w_ab f_b q_a = (Σ_a f_a q_a + (Σ f)(Σ q)) / 24.
    const Vec3 first =
        (f[0] * q[0] + f[1] * q[1] + f[2] * q[2] + (f[0] + f[1] + f[2]) * (q[0] + q[1] + q[2])) /
        24.0;
    w.tau += first.cross(s);
  }
  return w;
}

}  // namespace mrh::geometry
