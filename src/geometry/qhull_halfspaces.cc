// SPDX-License-Identifier: Apache-2.0
// qhull_r behind a silent, leak-free wrapper: halfspace intersection (the Muller–Preparata dual
// transform, thesis §3.2.1) and convex hulls.
#include "geometry/qhull_halfspaces.h"

#include <stdio.h>  // fopencookie (glibc)
#include <sys/types.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstring>
#include <memory>
#include <string_view>
#include <vector>

#include "mrh/geometry/contact_region.h"

// qhull's headers define macros (True, False, realT, FORALLfacets, ...): include them last.
extern "C" {
#include <libqhull_r/qhull_ra.h>
}

namespace mrh::geometry {
namespace {

// Two region vertices closer than this fraction of the region's extent are one vertex: qhull
// leaves a vertex where more than three planes meet as several facets of the dual hull unless
// it merged them, and the dual transform loses a few ulps per coordinate (1/e amplification).
constexpr double kVertexMergeRelTol = 1e-9;
// A returned vertex may violate an input halfspace by at most this fraction of the region's
// extent; more means qhull produced garbage (never seen, but cheap to rule out).
constexpr double kVertexCheckRelTol = 1e-6;

// A write-only stream that discards everything: qhull reports errors and warnings to the FILE it
// is given (stderr when given none), and the library must never print. fopencookie needs no
// file system, unlike /dev/null. Opened once; glibc streams are internally locked.
FILE* NullStream() {
  static FILE* const stream = [] {
    cookie_io_functions_t io{};
    io.write = [](void*, const char*, size_t size) -> ssize_t {
      return static_cast<ssize_t>(size);
    };
    return fopencookie(nullptr, "w", io);
  }();
  return stream;
}

// One qhull_r run: owns the qhT, runs qh_new_qhull (which sets its own setjmp error exit, so a
// qhull error returns an exit code instead of aborting) and frees all qhull memory on scope exit.
class QhullRun {
 public:
  QhullRun() : qh_(std::make_unique<qhT>()) {}

  QhullRun(const QhullRun&) = delete;
  QhullRun& operator=(const QhullRun&) = delete;

  ~QhullRun() {
    if (!started_) return;
    qh_freeqhull(qh_.get(), !qh_ALL);
    int still_long = 0;
    int still_total = 0;
    qh_memfreeshort(qh_.get(), &still_long, &still_total);
  }

  // Runs `command` on `count` points of dimension `dim`; true on success. The coordinates stay
  // owned by the caller (ismalloc = False).
  bool Run(int dim, std::vector<coordT>& coords, std::string_view command) {
    FILE* const silent = NullStream();
    if (silent == nullptr) return false;  // never let qhull fall back to stderr
    std::array<char, 32> cmd{};
    if (command.size() >= cmd.size()) return false;
    std::copy(command.begin(), command.end(), cmd.begin());
    qh_zero(qh_.get(), silent);
    started_ = true;
    const int count = static_cast<int>(coords.size()) / dim;
    const int exit_code =
        qh_new_qhull(qh_.get(), dim, count, coords.data(), False, cmd.data(), nullptr, silent);
    return exit_code == qh_ERRnone;
  }

  qhT* get() { return qh_.get(); }

 private:
  std::unique_ptr<qhT> qh_;
  bool started_ = false;
};

void AppendUnique(std::vector<Vec3>& points, const Vec3& p, double tolerance) {
  for (const Vec3& q : points) {
    if ((q - p).norm() <= tolerance) return;
  }
  points.push_back(p);
}

// Reads the intersection vertices off the dual hull, in the frame centred at the interior point.
// Each facet m·ŷ + offset = 0 (m unit, outward) of the hull of the dual points a_k / h_k maps
// back to the vertex m / e with e = −offset > 0 (the dual transform's inverse). e <= 0 means the
// origin is not inside the dual hull, i.e. the intersection is unbounded.
std::optional<std::vector<Vec3>> DualFacetsToVertices(qhT* qh) {
  std::vector<Vec3> raw;
  facetT* facet = nullptr;
  FORALLfacets {
    const double e = -facet->offset;
    if (!(e > 0.0)) return std::nullopt;
    const Vec3 p = Vec3(facet->normal[0], facet->normal[1], facet->normal[2]) / e;
    if (!IsFinite(p)) return std::nullopt;
    raw.push_back(p);
  }
  return raw;
}

}  // namespace

std::optional<std::vector<Vec3>> IntersectHalfspaces(std::span<const Halfspace> halfspaces,
                                                     const Vec3& interior) {
  // Fewer than 4 halfspaces never bound a volume in 3-D.
  if (halfspaces.size() < 4 || !IsFinite(interior)) return std::nullopt;
  // Shift the planes so that the interior point is the origin (qhull's feasible point "H0,0,0"):
  // qhull's halfspace row [a, offset] means a·y + offset <= 0, so offset = −h_k.
  std::vector<coordT> coords;
  coords.reserve(4 * halfspaces.size());
  for (const Halfspace& h : halfspaces) {
    const double slack = h.b - h.a.dot(interior);
    if (!IsFinite(h.a) || !std::isfinite(slack) || !(slack > 0.0)) return std::nullopt;
    coords.insert(coords.end(), {h.a.x(), h.a.y(), h.a.z(), -slack});
  }
  QhullRun run;
  if (!run.Run(4, coords, "qhull H0,0,0")) return std::nullopt;
  std::optional<std::vector<Vec3>> raw = DualFacetsToVertices(run.get());
  if (!raw || raw->size() < 4) return std::nullopt;

  double extent = 0.0;
  for (const Vec3& p : *raw) extent = std::max(extent, p.norm());
  std::vector<Vec3> vertices;
  for (const Vec3& p : *raw) AppendUnique(vertices, p, kVertexMergeRelTol * extent);
  for (Vec3& p : vertices) {
    for (const Halfspace& h : halfspaces) {
      if (h.a.dot(p) - (h.b - h.a.dot(interior)) > kVertexCheckRelTol * extent) {
        return std::nullopt;
      }
    }
    p += interior;
  }
  if (vertices.size() < 4) return std::nullopt;
  return vertices;
}

namespace internal {

std::optional<ConvexMesh> ConvexHullMesh(std::span<const Vec3> points) {
  if (points.size() < 4) return std::nullopt;
  std::vector<coordT> coords;
  coords.reserve(3 * points.size());
  for (const Vec3& p : points) {
    if (!IsFinite(p)) return std::nullopt;
    coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  }
  QhullRun run;
  // "Qt": triangulated output, so that every facet is a triangle of input points.
  if (!run.Run(3, coords, "qhull Qt")) return std::nullopt;
  qhT* const qh = run.get();
  ConvexMesh mesh;
  mesh.vertices.assign(points.begin(), points.end());
  const int count = static_cast<int>(points.size());
  facetT* facet = nullptr;
  FORALLfacets {
    std::array<int, 3> ids{};
    std::size_t k = 0;
    vertexT* vertex = nullptr;
    vertexT** vertexp = nullptr;
    FOREACHvertex_(facet->vertices) {
      if (k == ids.size()) return std::nullopt;
      ids[k++] = qh_pointid(qh, vertex->point);
    }
    if (k != ids.size()) return std::nullopt;
    for (int id : ids) {
      if (id < 0 || id >= count) return std::nullopt;
    }
    // qhull's vertex order says nothing about orientation: wind by the facet's outward normal.
    const Vec3& p0 = points[static_cast<std::size_t>(ids[0])];
    const Vec3 cross = (points[static_cast<std::size_t>(ids[1])] - p0)
                           .cross(points[static_cast<std::size_t>(ids[2])] - p0);
    const Vec3 outward(facet->normal[0], facet->normal[1], facet->normal[2]);
    if (cross.dot(outward) < 0.0) std::swap(ids[1], ids[2]);
    mesh.triangles.push_back(ids);
  }
  if (mesh.triangles.size() < 4) return std::nullopt;
  return mesh;
}

}  // namespace internal
}  // namespace mrh::geometry
