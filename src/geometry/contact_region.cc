// SPDX-License-Identifier: Apache-2.0
// Plane + contact points of a pointer/object pair from the penetration region (thesis §3.2.1).
#include "mrh/geometry/contact_region.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "geometry/deepest_point.h"
#include "geometry/region_vertices.h"

namespace mrh::geometry {
namespace {

// Object faces within this fraction of the pointer's size of the most violated one all pass
// through the touching point c; their mean normal is the contact normal when the witness points
// coincide (an edge contact gets the bisector of its two faces).
constexpr double kFaceTieRelTol = 1e-9;
// The witness midpoint is the interior point when its clearance to the nearest plane is at
// least this fraction of the largest possible one (the inscribed ball's radius).
constexpr double kWellInside = 0.1;

double Size(const ConvexPolyhedron& polyhedron) {
  double size = 0.0;
  for (const Vec3& v : polyhedron.vertices()) size = std::max(size, v.norm());
  return size;
}

Halfspace ToWorld(const Halfspace& h, const Pose& X_WS) {
  const Vec3 a_W = X_WS.q * h.a;
  return Halfspace{a_W, h.b + a_W.dot(X_WS.p)};
}

double Slack(const Halfspace& h, const Vec3& y) {
  return h.b - h.a.dot(y);
}

double MinSlack(std::span<const Halfspace> halfspaces, const Vec3& y) {
  double slack = std::numeric_limits<double>::infinity();
  for (const Halfspace& h : halfspaces) slack = std::min(slack, Slack(h, y));
  return slack;
}

// Mean world normal of the object faces through c (the object's outward normal there).
Vec3 ObjectNormalAt(const ConvexPolyhedron& object, const Pose& X_WO, const Vec3& c,
                    double tolerance) {
  double most = -std::numeric_limits<double>::infinity();
  for (const Halfspace& h : object.faces()) most = std::max(most, -Slack(ToWorld(h, X_WO), c));
  Vec3 sum = Vec3::Zero();
  for (const Halfspace& h : object.faces()) {
    const Halfspace h_W = ToWorld(h, X_WO);
    if (-Slack(h_W, c) >= most - tolerance) sum += h_W.a;
  }
  return sum.norm() > 0.0 ? Vec3(sum.normalized()) : Vec3(X_WO.q * Vec3::UnitZ());
}

// Object → pointer: from B's witness to A's when separated, along the penetration vector from
// A's witness to B's when penetrating. Witness points closer than the touching tolerance give
// no direction: use the object's face normal at c instead.
Vec3 PlaneNormal(const ConvexPolyhedron& object, const Pose& X_WO, const DistanceResult& d,
                 double touching_tolerance, double face_tolerance) {
  const Vec3 w = d.distance < 0.0 ? Vec3(d.p_WB - d.p_WA) : Vec3(d.p_WA - d.p_WB);
  const double length = w.norm();
  if (std::isfinite(length) && length > touching_tolerance) return w / length;
  return ObjectNormalAt(object, X_WO, d.p_WB, face_tolerance);
}

// Fallback for a pair that is separated or touching, or whose region cannot be analysed (the
// thesis is silent; Springhead does the same): the pointer-side witness point is the only
// contact point, so the haptic side still sees a contact that begins between two physics steps.
ContactRegion Fallback(RegionStatus status, const DistanceResult& d, const Vec3& n) {
  ContactRegion region;
  region.status = status;
  region.distance = d.distance;
  region.n_W = n;
  region.c_W = d.p_WB;
  region.points_W = {d.p_WA};
  region.depths = {n.dot(d.p_WB - d.p_WA)};
  return region;
}

// The pointer's faces and the object faces that cut the pointer, in world. An object face that
// the whole pointer satisfies cannot cut the intersection; dropping it keeps qhull's input small
// for finely tessellated objects. (Only one side may be pruned: pruning both could drop every
// face of two coinciding boxes.)
std::vector<Halfspace> PairHalfspaces(const ConvexPolyhedron& pointer, const Pose& X_WP,
                                      const ConvexPolyhedron& object, const Pose& X_WO) {
  std::vector<Vec3> pointer_W;
  pointer_W.reserve(pointer.vertices().size());
  for (const Vec3& v : pointer.vertices()) pointer_W.push_back(X_WP * v);
  std::vector<Halfspace> halfspaces;
  halfspaces.reserve(pointer.faces().size() + object.faces().size());
  for (const Halfspace& h : pointer.faces()) halfspaces.push_back(ToWorld(h, X_WP));
  for (const Halfspace& h : object.faces()) {
    const Halfspace h_W = ToWorld(h, X_WO);
    const bool cuts = std::any_of(pointer_W.begin(), pointer_W.end(), [&](const Vec3& v) {
      return Slack(h_W, v) < 0.0;
    });
    if (cuts) halfspaces.push_back(h_W);
  }
  return halfspaces;
}

// Where qhull's dual transform is centred: a point strictly inside every halfspace, or the
// fallback status when there is none. kTouching when the intersection has no volume (its
// largest inscribed ball has radius <= tolerance: the dual transform needs an interior point),
// kFailed when that ball
// cannot be found.
struct Interior {
  std::optional<Vec3> point;
  RegionStatus fallback = RegionStatus::kFailed;
};

// The witness midpoint o (the thesis' origin for the dual transform, §3.2.1) when it is well
// inside; otherwise the Chebyshev centre.
// o is not always inside: FCL's EPA witnesses of an edge–edge penetration lie on the two edges,
// and beside a sharp edge the segment between them leaves the other body; the polyhedra of
// curved shapes also lie up to their approximation error inside the surfaces the witnesses
// are on. A point barely inside would make qhull's dual points (a_k / h_k) huge.
Interior InteriorPoint(std::span<const Halfspace> halfspaces, const DistanceResult& d,
                       double tolerance) {
  const Vec3 o = 0.5 * (d.p_WA + d.p_WB);
  const std::optional<internal::InscribedBall> ball = internal::DeepestPoint(halfspaces, o);
  if (!ball) return Interior{std::nullopt, RegionStatus::kFailed};
  if (!(ball->radius > tolerance)) return Interior{std::nullopt, RegionStatus::kTouching};
  const double o_slack = MinSlack(halfspaces, o);
  if (o_slack > tolerance && o_slack >= kWellInside * ball->radius) return Interior{o};
  return Interior{ball->centre};
}

// How far the plane through c lies above the object polyhedron's supporting plane along n:
// zero for exact shapes, up to the approximation error for an inscribed curved object, whose
// region vertices on its own surface then lie below the plane without being pointer points.
double PlaneClearance(const ConvexPolyhedron& object, const Pose& X_WO, const Vec3& n,
                      const Vec3& c) {
  if (object.unbounded()) return 0.0;
  const Vec3 n_O = X_WO.q.conjugate() * n;
  double support = -std::numeric_limits<double>::infinity();
  for (const Vec3& v : object.vertices()) support = std::max(support, n_O.dot(v));
  return std::max(0.0, n.dot(c) - (support + n.dot(X_WO.p)));
}

void AppendUnique(std::vector<Vec3>& points, std::vector<double>& depths, const Vec3& p,
                  double depth, double tolerance) {
  for (const Vec3& q : points) {
    if ((q - p).norm() <= tolerance) return;
  }
  points.push_back(p);
  depths.push_back(depth);
}

}  // namespace

namespace internal {

std::optional<std::vector<Vec3>> RegionVertices(const ConvexPolyhedron& a, const Pose& X_WA,
                                                const ConvexPolyhedron& b, const Pose& X_WB,
                                                const DistanceResult& d,
                                                double touching_tolerance) {
  if (a.unbounded() || d.distance >= -touching_tolerance) return std::nullopt;
  const std::vector<Halfspace> halfspaces = PairHalfspaces(a, X_WA, b, X_WB);
  const Interior interior = InteriorPoint(halfspaces, d, touching_tolerance);
  if (!interior.point) return std::nullopt;
  return IntersectHalfspaces(halfspaces, *interior.point);
}

}  // namespace internal

ContactRegion ComputeContactRegion(const ConvexPolyhedron& pointer, const Pose& X_WP,
                                   const ConvexPolyhedron& object, const Pose& X_WO,
                                   const DistanceResult& d, const RegionOptions& options) {
  const double face_tolerance = kFaceTieRelTol * Size(pointer);
  const Vec3 n = PlaneNormal(object, X_WO, d, options.touching_tolerance, face_tolerance);
  if (d.distance > options.touching_tolerance) return Fallback(RegionStatus::kSeparated, d, n);
  // A plane pointer would leave the region unbounded (the pointer is never a plane).
  if (pointer.unbounded()) return Fallback(RegionStatus::kFailed, d, n);
  if (d.distance >= -options.touching_tolerance) return Fallback(RegionStatus::kTouching, d, n);

  // Zero-volume guard: without a point strictly inside both polyhedra the
  // region has no volume to analyse, and qhull would fail on it.
  const std::vector<Halfspace> halfspaces = PairHalfspaces(pointer, X_WP, object, X_WO);
  const Interior interior = InteriorPoint(halfspaces, d, options.touching_tolerance);
  if (!interior.point) return Fallback(interior.fallback, d, n);
  const std::optional<std::vector<Vec3>> vertices =
      IntersectHalfspaces(halfspaces, *interior.point);
  if (!vertices) return Fallback(RegionStatus::kFailed, d, n);

  // Contact points: the region's vertices below the plane through c; the ones on it (within
  // the tolerance) are where the object's surface bounds the region (thesis §3.2.1). For a curved
  // object "on it" means on the polyhedron's supporting plane, while depths stay measured from
  // c on the true surface.
  const double clearance = PlaneClearance(object, X_WO, n, d.p_WB);
  ContactRegion region;
  region.status = RegionStatus::kRegion;
  region.distance = d.distance;
  region.n_W = n;
  region.c_W = d.p_WB;
  for (const Vec3& p : *vertices) {
    const double depth = n.dot(d.p_WB - p);
    if (depth - clearance > options.on_plane_tolerance) {
      AppendUnique(region.points_W, region.depths, p, depth, options.on_plane_tolerance);
    }
  }
  // A region thinner than the on-plane tolerance is a touching contact.
  if (region.points_W.empty()) return Fallback(RegionStatus::kTouching, d, n);
  return region;
}

}  // namespace mrh::geometry
