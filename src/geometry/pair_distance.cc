// SPDX-License-Identifier: Apache-2.0
// Distance between prepared shapes: FCL GJK/EPA on the shapes' cores where it is reliable, closed
// forms and the separating axis test where it is not, then inflation by the radii.
//
// Spheres and capsules are a core (a point or a segment) inflated by their radius, so FCL sees
// only polytopes or genuinely curved shapes (cylinder, ellipsoid). Measured on FCL 0.7: on a
// curved surface libccd's EPA places witness points only to about the square root of its
// tolerance and, below a tolerance of ~3e-8 at unit size or at millimetre sizes, trips FCL's own
// assertions; on a sphere centred exactly on a box corner it never terminates; GJK and EPA abort
// on a point or segment exactly touching a polytope, a cylinder or an ellipsoid. Hence sphere and
// capsule pairs and spheres against cylinders are closed form, a point or segment against a box
// or mesh goes through the separating axis test first, and pairs with a cylinder or an ellipsoid
// are rescaled to unit size (by a power of two, which is exact) before FCL sees them.
#include <algorithm>
#include <array>
#include <cmath>
#include <optional>

#include "geometry/fcl_query.h"
#include "geometry/point_surface.h"
#include "geometry/prepared_shape.h"
#include "geometry/segment_distance.h"
#include "geometry/segment_exit.h"
#include "geometry/support.h"

namespace mrh::geometry::internal {
namespace {

// GJK stopping tolerance (relative to the pair's size) for separated shapes. On polytopes GJK
// stops anyway once it no longer improves; on curved shapes this puts the witness points within
// ~4e-9 of the surface. (FCL's signed query runs a GJK that stops at the EPA tolerance, whose
// witness points on a cylinder rim lie up to 8e-4 of the size inside the surface.)
constexpr double kGjkTolerance = 1e-12;
// EPA stopping tolerance on polytope pairs, relative to the pair's size. Fuzzing FCL 0.7 on
// boxes, convex meshes, points and segments showed no failure down to 1e-12.
constexpr double kPolytopeEpaTolerance = 1e-9;
// EPA stopping tolerance on pairs with a curved FCL shape, relative to the pair rescaled to unit
// size: 30x above the onset of FCL assertion failures (3e-8). The depth is then good to ~1e-6 of
// the size and the witness direction to ~1e-3 rad.
constexpr double kCurvedEpaTolerance = 1e-6;
// Cores closer than this (relative to the pair's size) count as touching: the direction along
// which to inflate them by their radii is then undefined and found another way.
constexpr double kCoreTouchTolerance = 1e-10;
// How far a touching core is pushed into the other shape (relative to the size) to find its
// normal: well above kCoreTouchTolerance and EPA's tolerance, small enough to stay on the same
// face (exact on polytopes; on a curved surface the normal tilts by about this angle).
constexpr double kTouchPush = 1e-4;
// A sphere centre or capsule axis within this distance (relative to the size) of a box, mesh or
// ellipsoid is treated as touching it: the separating axis test or a first-order closed form
// (error ~1e-12 of the size) answers, as FCL's GJK asserts on exact contact.
constexpr double kSurfaceBand = 1e-6;
// How far (relative to the size) a core overlapping a polytope is moved clear of it along the
// separating axis before GJK looks for the touching pair: any positive distance works.
constexpr double kExitClearance = 0.125;
// FCL's EPA throws on some exactly aligned configurations (a box centred on another's corner,
// say). Retrying with B moved by this (relative to the size) along a generic direction breaks
// the alignment at a cost of that much accuracy.
constexpr double kNudge = 1e-8;
const std::array<Vec3, 3> kNudgeDirections = {Vec3(0.31, 0.52, 0.79), Vec3(-0.67, 0.23, 0.41),
                                              Vec3(0.12, -0.85, -0.37)};

// Moves the core witness points outward by the radii along n (unit, from A toward B).
FclDistance Inflate(const FclDistance& core, const Vec3& n, double margin_a, double margin_b) {
  return FclDistance{core.distance - margin_a - margin_b, core.p_A + margin_a * n,
                     core.p_B - margin_b * n};
}

// GJK alone first, with a tight tolerance; EPA only when the shapes overlap.
std::optional<FclDistance> GjkThenEpa(const FclGeometry& a, const FclGeometry& b, const Pose& X_AB,
                                      double size, double epa_tolerance) {
  const std::optional<FclDistance> separation =
      FclQuery(a, b, X_AB, kGjkTolerance * size, /*signed_distance=*/false);
  if (separation && separation->distance >= 0.0) return separation;
  return FclQuery(a, b, X_AB, epa_tolerance, /*signed_distance=*/true);
}

// GjkThenEpa, retried with B nudged by a tiny generic offset when FCL fails on an exactly
// aligned configuration; B's witness point is moved back by the nudge.
std::optional<FclDistance> RobustFcl(const FclGeometry& a, const FclGeometry& b, const Pose& X_AB,
                                     double size, double epa_tolerance) {
  if (auto r = GjkThenEpa(a, b, X_AB, size, epa_tolerance)) return r;
  for (const Vec3& direction : kNudgeDirections) {
    const Vec3 nudge = kNudge * size * direction.normalized();
    if (auto r = GjkThenEpa(a, b, Pose{X_AB.p + nudge, X_AB.q}, size, epa_tolerance)) {
      r->p_B -= nudge;
      return r;
    }
  }
  return std::nullopt;
}

// FCL on the cores of a pair rescaled (by a power of two, so exactly) to a size in [1, 2).
std::optional<FclDistance> NormalizedCoreFcl(const Shape& a, const Shape& b, double size,
                                             const Pose& X_AB) {
  const double scale = std::ldexp(1.0, -std::ilogb(size));
  const auto fcl_a = MakeFclGeometry(a, scale, /*core=*/true);
  const auto fcl_b = MakeFclGeometry(b, scale, /*core=*/true);
  const std::optional<FclDistance> r =
      RobustFcl(*fcl_a, *fcl_b, Pose{scale * X_AB.p, X_AB.q}, scale * size, kCurvedEpaTolerance);
  if (!r) return std::nullopt;
  return FclDistance{r->distance / scale, r->p_A / scale, r->p_B / scale};
}

// Support point of a shape's core along u (shape frame).
Vec3 CoreSupport(const PreparedShape& s, const Vec3& u) {
  switch (s.core) {
    case Core::kPoint:
      return Vec3::Zero();
    case Core::kSegment:
      return Vec3(0.0, 0.0, u.z() >= 0.0 ? s.half_length : -s.half_length);
    case Core::kSolid:
    case Core::kPlane:
      break;
  }
  return SupportPoint(s.shape, u);
}

// Last resort where FCL failed even on nudged poses: the cores' extent along the line of their
// centres. A valid separating-axis estimate, not the exact distance.
FclDistance CentreLineEstimate(const PreparedShape& a, const PreparedShape& b, const Pose& X_AB) {
  const Vec3 line = X_AB * b.centre - a.centre;
  const Vec3 n = line.isZero(0.0) ? Vec3::UnitZ() : Vec3(line.normalized());
  const Vec3 p_A = CoreSupport(a, n);
  const Vec3 p_B = X_AB * CoreSupport(b, X_AB.q.conjugate() * (-n));
  return FclDistance{n.dot(p_B - p_A), p_A, p_B};
}

// A direction separating two touching cores (segments d_a, d_b; a zero vector is a point) whose
// centres are offset by c: the common normal of the segments, else any normal of the longer
// one, oriented from A toward B.
Vec3 TouchingCoreNormal(const Vec3& d_a, const Vec3& d_b, const Vec3& c) {
  Vec3 n = d_a.cross(d_b);
  if (n.squaredNorm() <= 1e-20 * d_a.squaredNorm() * d_b.squaredNorm() || n.isZero(0.0)) {
    const Vec3 axis = d_a.squaredNorm() >= d_b.squaredNorm() ? d_a : d_b;
    n = axis.isZero(0.0) ? c : c - c.dot(axis) / axis.squaredNorm() * axis;
    if (n.isZero(0.0)) n = axis.isZero(0.0) ? Vec3::UnitX() : Vec3(axis.unitOrthogonal());
  }
  n.normalize();
  return n.dot(c) < 0.0 ? -n : n;
}

// Sphere/capsule pairs in closed form: closest points of the cores, inflated by the radii.
FclDistance CoreCoreDistance(const PreparedShape& a, const PreparedShape& b, const Pose& X_AB) {
  const Vec3 half_a(0.0, 0.0, a.half_length);
  const Vec3 half_b = X_AB.q * Vec3(0.0, 0.0, b.half_length);
  const SegmentClosestPoints c =
      ClosestPointsOnSegments(-half_a, half_a, X_AB.p - half_b, X_AB.p + half_b);
  const FclDistance core{c.distance, c.p_a, c.p_b};
  const double size = std::max(a.radius, b.radius);
  const Vec3 n = c.distance > kCoreTouchTolerance * size
                     ? Vec3((c.p_b - c.p_a) / c.distance)
                     : TouchingCoreNormal(2.0 * half_a, 2.0 * half_b, X_AB.p);
  return Inflate(core, n, a.margin, b.margin);
}

// FCL on the cores of a pair other than sphere/capsule against sphere/capsule.
FclDistance CoreFcl(const PreparedShape& a, const PreparedShape& b, const Pose& X_AB, double size) {
  const std::optional<FclDistance> r =
      a.curved || b.curved
          ? NormalizedCoreFcl(a.shape, b.shape, size, X_AB)
          : RobustFcl(*a.fcl_core, *b.fcl_core, X_AB, size, kPolytopeEpaTolerance * size);
  return r ? *r : CentreLineEstimate(a, b, X_AB);
}

// Unit direction from A toward B along witness points, or none when they (nearly) coincide.
std::optional<Vec3> WitnessDirection(const FclDistance& r, double size) {
  const Vec3 gap = r.p_B - r.p_A;  // separated: along A→B; penetrating: along B→A
  const double norm = gap.norm();
  if (norm <= kCoreTouchTolerance * size) return std::nullopt;
  return Vec3((r.distance > 0.0 ? 1.0 : -1.0) / norm * gap);
}

// A sphere centre or capsule axis on the other (solid) shape's surface leaves no gap to inflate
// along. Pushing the core a little into the solid, toward an interior point, makes the cores
// overlap, and EPA then gives the solid's surface normal there. (FCL on the whole shapes is not
// an option: its EPA never terminates for a sphere centred exactly on a box corner.)
FclDistance TouchingCoresDistance(const PreparedShape& a, const PreparedShape& b, const Pose& X_AB,
                                  double size, const FclDistance& touching) {
  const bool a_is_core = a.margin > 0.0;  // sphere/capsule pairs never get here: one is solid
  const Vec3 contact = 0.5 * (touching.p_A + touching.p_B);
  Vec3 inward = (a_is_core ? X_AB * b.centre : a.centre) - contact;
  inward = inward.isZero(0.0) ? Vec3::UnitX() : Vec3(inward.normalized());
  // Moving B by `shift` moves A relative to B by -shift.
  const Vec3 shift = (a_is_core ? -kTouchPush : kTouchPush) * size * inward;
  const FclDistance pushed = CoreFcl(a, b, Pose{X_AB.p + shift, X_AB.q}, size);
  std::optional<Vec3> n = pushed.distance < 0.0 ? WitnessDirection(pushed, size) : std::nullopt;
  // Should EPA fail, the direction into (or out of) the solid still separates the pair.
  if (!n) n = a_is_core ? inward : Vec3(-inward);
  return Inflate(touching, *n, a.margin, b.margin);
}

// The deepest point of the core and the point where it exits the solid, from the separating axis
// alone (solid frame). Used only should GJK fail on the separated configuration.
FclDistance ExitWitnesses(const SegmentExit& exit, const Pose& X_SC, double half_length) {
  const Vec3 half = X_SC.q * Vec3(0.0, 0.0, half_length);
  const double side = exit.u.dot(half);
  const Vec3 deepest = X_SC.p - (side > 0.0 ? half : side < 0.0 ? Vec3(-half) : Vec3::Zero());
  return FclDistance{-exit.depth, deepest, deepest + exit.depth * exit.u};
}

// A sphere centre or capsule axis against a box or mesh. The separating axis test comes first:
// FCL's GJK and EPA abort on such zero-volume cores touching a polytope (measured on FCL 0.7), so
// FCL only sees them clearly apart. A core that is clear by more than kSurfaceBand goes to GJK
// as is; otherwise the test gives the depth and direction, and GJK finds the witness points with
// the core moved clear along that axis (which keeps the touching pair the closest pair).
FclDistance ThinCoreAndPolytope(const PreparedShape& a, const PreparedShape& b, const Pose& X_AB,
                                double size) {
  const bool a_is_core = a.margin > 0.0;
  const PreparedShape& core = a_is_core ? a : b;
  const PreparedShape& solid = a_is_core ? b : a;
  const Pose X_SC = a_is_core ? X_AB.Inverse() : X_AB;  // the core in the solid's frame
  const SegmentExit exit =
      ExitSegment(solid.shape, solid.features, X_SC.p, X_SC.q * Vec3(0.0, 0.0, core.half_length));
  if (exit.depth < -kSurfaceBand * size) {
    const std::optional<FclDistance> gap =
        FclQuery(*a.fcl_core, *b.fcl_core, X_AB, kGjkTolerance * size, /*signed_distance=*/false);
    const std::optional<Vec3> n =
        gap && gap->distance >= 0.0 ? WitnessDirection(*gap, size) : std::nullopt;
    if (n) return Inflate(*gap, *n, a.margin, b.margin);
  }
  // Direction from A toward B, in A's frame: the core leaves the solid along exit.u.
  const Vec3 n = a_is_core ? Vec3(-(X_AB.q * exit.u)) : exit.u;
  const Vec3 shift = (std::max(exit.depth, 0.0) + kExitClearance * size) * n;  // B moves by it
  const std::optional<FclDistance> apart =
      FclQuery(*a.fcl_core, *b.fcl_core, Pose{X_AB.p + shift, X_AB.q}, kGjkTolerance * size, false);
  FclDistance touching{-exit.depth, Vec3::Zero(), Vec3::Zero()};
  if (apart && apart->distance >= 0.0) {
    touching.p_A = apart->p_A;
    touching.p_B = apart->p_B - shift;
  } else {
    const FclDistance w = ExitWitnesses(exit, X_SC, core.half_length);
    const Pose& X_AS = a_is_core ? X_AB : Pose::Identity();
    touching.p_A = X_AS * (a_is_core ? w.p_A : w.p_B);
    touching.p_B = X_AS * (a_is_core ? w.p_B : w.p_A);
  }
  return Inflate(touching, n, a.margin, b.margin);
}

// A sphere centre against a cylinder, or near an ellipsoid's surface, in closed form (FCL's GJK
// asserts on a point exactly on either). Returns nothing when FCL should answer.
std::optional<FclDistance> SphereCurvedDistance(const PreparedShape& a, const PreparedShape& b,
                                                const Pose& X_AB, double size) {
  const bool a_is_sphere = a.core == Core::kPoint;
  const PreparedShape& solid = a_is_sphere ? b : a;
  const Pose X_SC = a_is_sphere ? X_AB.Inverse() : X_AB;  // the sphere centre in the solid
  std::optional<PointSurface> c;
  if (solid.shape.type == ShapeType::kCylinder) {
    c = PointToCylinder(solid.shape.size.x(), solid.shape.size.y(), X_SC.p);
  } else {
    c = PointNearEllipsoid(solid.shape.size, X_SC.p, kSurfaceBand * size);
  }
  if (!c) return std::nullopt;
  // Map to A's frame; the normal points out of the solid, toward the sphere centre.
  const Pose& X_AS = a_is_sphere ? X_AB : Pose::Identity();
  const Vec3 n = X_AS.q * (a_is_sphere ? Vec3(-c->normal) : c->normal);
  const FclDistance core = a_is_sphere ? FclDistance{c->distance, X_AS * X_SC.p, X_AS * c->surface}
                                       : FclDistance{c->distance, c->surface, X_SC.p};
  return Inflate(core, n, a.margin, b.margin);
}

// Any other pair of non-planes: FCL on the cores, then inflation by the radii.
FclDistance FclPairDistance(const PreparedShape& a, const PreparedShape& b, const Pose& X_AB) {
  const double size = std::max(a.radius, b.radius);
  if (a.margin == 0.0 && b.margin == 0.0) return CoreFcl(a, b, X_AB, size);
  if (a.polytope || b.polytope) return ThinCoreAndPolytope(a, b, X_AB, size);
  if ((a.core == Core::kPoint && b.curved) || (b.core == Core::kPoint && a.curved)) {
    if (auto r = SphereCurvedDistance(a, b, X_AB, size)) return *r;
  }
  const FclDistance core = CoreFcl(a, b, X_AB, size);
  const std::optional<Vec3> n = WitnessDirection(core, size);
  if (!n) return TouchingCoresDistance(a, b, X_AB, size, core);
  return Inflate(core, *n, a.margin, b.margin);
}

}  // namespace

FclDistance PairDistance(const PreparedShape& a, const PreparedShape& b, const Pose& X_AB) {
  const bool core_core = a.core != Core::kSolid && b.core != Core::kSolid;
  return core_core ? CoreCoreDistance(a, b, X_AB) : FclPairDistance(a, b, X_AB);
}

}  // namespace mrh::geometry::internal
