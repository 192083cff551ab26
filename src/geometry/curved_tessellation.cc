// SPDX-License-Identifier: Apache-2.0
// Latitude–longitude tessellations of sphere, capsule and ellipsoid, polygonal cylinders, and
// the closed-form distance between each and its true surface.
#include "geometry/curved_tessellation.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace mrh::geometry::internal {
namespace {

constexpr double kPi = std::numbers::pi;

// Distance from the centre of the unit sphere to the plane of the grid face spanning longitudes
// ±beta and latitudes mu ± delta/2. The face is symmetric about its middle meridian plane, where
// its plane is the line through the midpoints (cos(phi) cos(beta), sin(phi)) of its two
// horizontal edges (phi = mu ± delta/2; a polar face has the pole as the second point); the
// distance from the origin to that chord simplifies to
//   cos(beta) cos(delta/2) / sqrt(cos^2(mu) + cos^2(beta) sin^2(mu)).
// It grows with |mu|, so the band nearest the equator is the worst. Since every vertex lies on
// the sphere, the ball of this radius is inside the polyhedron, and the face's foot point lies
// inside the face: 1 − distance is exactly the largest gap to the surface.
double BandPlaneDistance(double beta, double delta, double mu) {
  const double cb = std::cos(beta);
  const double cm = std::cos(mu);
  const double sm = std::sin(mu);
  return cb * std::cos(0.5 * delta) / std::sqrt(cm * cm + cb * cb * sm * sm);
}

// Sphere with `bands` from pole to pole: an odd count puts a band across the equator (mu = 0),
// an even count puts a ring on it (nearest bands at mu = ±delta/2).
double SpherePlaneDistance(int longitudes, int bands) {
  const double delta = kPi / bands;
  return BandPlaneDistance(kPi / longitudes, delta, bands % 2 == 1 ? 0.0 : 0.5 * delta);
}

// Capsule with `bands` per cap: the side faces are at cos(beta), the cap band next to the
// equator ring (mu = delta/2) is always closer to the centre than that.
double CapsulePlaneDistance(int longitudes, int bands) {
  const double beta = kPi / longitudes;
  const double delta = 0.5 * kPi / bands;
  return std::min(std::cos(beta), BandPlaneDistance(beta, delta, 0.5 * delta));
}

// Fewest faces among grids whose plane distance reaches cos(π/segments). A grid needs more
// meridians than `segments` (a face spans some latitude too), and 4x is always enough.
template <typename PlaneDistance>
SphereGrid CoarsestGrid(int segments, int min_bands, PlaneDistance plane_distance,
                        int faces_per_longitude_and_band, int extra_faces_per_longitude) {
  const double target = std::cos(kPi / segments);
  SphereGrid best;
  long best_faces = std::numeric_limits<long>::max();
  for (int longitudes = segments + 1; longitudes <= 4 * segments; ++longitudes) {
    for (int bands = min_bands; bands <= 4 * segments; ++bands) {
      const double d = plane_distance(longitudes, bands);
      if (d < target) continue;
      const long faces = static_cast<long>(longitudes) *
                         (faces_per_longitude_and_band * bands + extra_faces_per_longitude);
      if (faces < best_faces) best = SphereGrid{longitudes, bands, d};
      best_faces = std::min(best_faces, faces);
      break;  // more bands only add faces
    }
  }
  return best;
}

Vec3 OnUnitSphere(double latitude, double longitude) {
  return Vec3(std::cos(latitude) * std::cos(longitude), std::cos(latitude) * std::sin(longitude),
              std::sin(latitude));
}

double Longitude(int i, int longitudes) {
  return 2.0 * kPi * i / longitudes;
}

// Grid points of the unit sphere scaled per axis (an ellipsoid's points stay on its surface).
std::vector<Vec3> ScaledSpherePoints(const SphereGrid& grid, const Vec3& radii) {
  std::vector<Vec3> points{Vec3(0, 0, -radii.z()), Vec3(0, 0, radii.z())};
  for (int j = 1; j < grid.bands; ++j) {
    const double latitude = -0.5 * kPi + kPi * j / grid.bands;
    for (int i = 0; i < grid.longitudes; ++i) {
      points.push_back(OnUnitSphere(latitude, Longitude(i, grid.longitudes)).cwiseProduct(radii));
    }
  }
  return points;
}

std::vector<Vec3> CapsulePoints(const SphereGrid& grid, double radius, double half_length) {
  std::vector<Vec3> points;
  for (const double side : {1.0, -1.0}) {
    points.emplace_back(0.0, 0.0, side * (half_length + radius));
    // With a zero half-length both caps share their equator ring: emit it once.
    const int first = (side < 0.0 && half_length == 0.0) ? 1 : 0;
    for (int j = first; j < grid.bands; ++j) {
      const double latitude = 0.5 * kPi * j / grid.bands;
      for (int i = 0; i < grid.longitudes; ++i) {
        Vec3 p = radius * OnUnitSphere(latitude, Longitude(i, grid.longitudes));
        p.z() = side * (half_length + p.z());
        points.push_back(p);
      }
    }
  }
  return points;
}

std::vector<Vec3> CylinderPoints(int segments, double radius, double half_height) {
  std::vector<Vec3> points;
  for (const double z : {half_height, -half_height}) {
    for (int i = 0; i < segments; ++i) {
      const double longitude = Longitude(i, segments);
      points.emplace_back(radius * std::cos(longitude), radius * std::sin(longitude), z);
    }
  }
  return points;
}

}  // namespace

SphereGrid SphereGridFor(int curved_segments) {
  // A sphere face is one longitude step by one band: longitudes * bands faces.
  return CoarsestGrid(curved_segments, 2, SpherePlaneDistance, 1, 0);
}

SphereGrid CapsuleGridFor(int curved_segments) {
  // Two caps of `bands` bands each plus one ring of side faces.
  return CoarsestGrid(curved_segments, 1, CapsulePlaneDistance, 2, 1);
}

std::vector<Vec3> CurvedShapePoints(const Shape& shape, int curved_segments) {
  const Vec3& s = shape.size;
  switch (shape.type) {
    case ShapeType::kSphere:
      return ScaledSpherePoints(SphereGridFor(curved_segments), Vec3::Constant(s.x()));
    case ShapeType::kEllipsoid:
      return ScaledSpherePoints(SphereGridFor(curved_segments), s);
    case ShapeType::kCapsule:
      return CapsulePoints(CapsuleGridFor(curved_segments), s.x(), s.y());
    case ShapeType::kCylinder:
      return CylinderPoints(curved_segments, s.x(), s.y());
    default:
      return {};
  }
}

double CurvedApproximationError(const Shape& shape, int curved_segments) {
  const Vec3& s = shape.size;
  switch (shape.type) {
    case ShapeType::kSphere:
      return s.x() * (1.0 - SphereGridFor(curved_segments).plane_distance);
    case ShapeType::kEllipsoid:
      // The polyhedron is the unit-sphere polyhedron scaled per axis, so it contains the
      // ellipsoid scaled by plane_distance: every gap is at most (1 − d) |x| <= (1 − d) r_max.
      return s.maxCoeff() * (1.0 - SphereGridFor(curved_segments).plane_distance);
    case ShapeType::kCapsule:
      return s.x() * (1.0 - CapsuleGridFor(curved_segments).plane_distance);
    case ShapeType::kCylinder:
      // An inscribed regular polygon is r cos(π/n) from its centre at each edge midpoint.
      return s.x() * (1.0 - std::cos(kPi / curved_segments));
    default:
      return 0.0;
  }
}

}  // namespace mrh::geometry::internal
