// SPDX-License-Identifier: Apache-2.0
// Convex polyhedra (vertices + unit-normal face halfspaces) built from shapes, for 6-DOF contact.
#pragma once

#include <span>
#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/geometry/shape.h"

namespace mrh::geometry {

/// The halfspace {y : a·y <= b} with unit outward normal a (frame given by the owner; m).
struct Halfspace {
  Vec3 a = Vec3::UnitZ();
  double b = 0.0;
};

/// A convex polyhedron in its shape frame: vertices, and faces as halfspaces (one per planar
/// face, coplanar triangles merged). A MuJoCo plane is unbounded: one halfspace (z <= 0), no
/// vertices. Immutable after construction; copying is cheap enough for setup, not for the RT path.
class ConvexPolyhedron {
 public:
  /// Box and convex mesh exactly; plane as its halfspace; sphere, capsule, cylinder and
  /// ellipsoid as inscribed polyhedra (vertices on the surface) at a resolution of
  /// `curved_segments` segments per full turn (>= 6): a cylinder is a `curved_segments`-gon
  /// prism; a sphere, capsule or ellipsoid is the coarsest latitude–longitude grid whose error
  /// is no larger than that polygon's (it needs more meridians, see ApproximationError).
  /// @throws mrh::InvalidArgument for a degenerate shape or curved_segments < 6.
  static ConvexPolyhedron FromShape(const Shape& shape, int curved_segments);
  /// Convex hull of points (qhull_r). @throws mrh::InvalidArgument if they span no volume.
  static ConvexPolyhedron FromPoints(std::span<const Vec3> points);

  const std::vector<Vec3>& vertices() const { return vertices_; }

  const std::vector<Halfspace>& faces() const { return faces_; }

  /// True for a plane (no vertices; the only face is z <= 0).
  bool unbounded() const { return vertices_.empty(); }

  /// Largest distance between the true surface of `shape` and FromShape(shape, segments) (m);
  /// 0 for box, mesh and plane. At most r(1 − cos(π/segments)) (r: radius; the largest radius
  /// of an ellipsoid): equal to it for a cylinder, exact and slightly below it for a sphere or
  /// capsule, an upper bound for an ellipsoid. @throws like FromShape. Not RT-safe.
  static double ApproximationError(const Shape& shape, int curved_segments);

 private:
  std::vector<Vec3> vertices_;
  std::vector<Halfspace> faces_;
};

}  // namespace mrh::geometry
