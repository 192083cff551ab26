// SPDX-License-Identifier: Apache-2.0
// Points against curved solids in closed form: FCL's GJK asserts on a point exactly on a
// cylinder's side or an ellipsoid (measured on FCL 0.7), e.g. a sphere resting on one.
#include "geometry/point_surface.h"

#include <algorithm>
#include <cmath>

namespace mrh::geometry::internal {

PointSurface PointToCylinder(double r, double h, const Vec3& p) noexcept {
  const double rho = std::hypot(p.x(), p.y());
  const Vec3 radial = rho > 0.0 ? Vec3(p.x() / rho, p.y() / rho, 0.0) : Vec3::UnitX();
  PointSurface out;
  if (rho > r || std::abs(p.z()) > h) {
    // Outside: clamp radially and axially.
    out.surface = Vec3(rho > r ? r * radial.x() : p.x(), rho > r ? r * radial.y() : p.y(),
                       std::clamp(p.z(), -h, h));
    const Vec3 gap = p - out.surface;
    out.distance = gap.norm();
    // Roundoff can put a point on the surface "outside" at distance 0: then it is on the surface.
    if (out.distance > 0.0) {
      out.normal = gap / out.distance;
      return out;
    }
  }
  // Inside (or on the surface): leave through the nearer of the side and the caps.
  const double side = r - rho;
  const double cap = h - std::abs(p.z());
  if (side < cap) {
    out.distance = -side;
    out.surface = Vec3(r * radial.x(), r * radial.y(), p.z());
    out.normal = radial;
  } else {
    const double up = p.z() >= 0.0 ? 1.0 : -1.0;
    out.distance = -cap;
    out.surface = Vec3(p.x(), p.y(), up * h);
    out.normal = Vec3(0.0, 0.0, up);
  }
  return out;
}

std::optional<PointSurface> PointNearEllipsoid(const Vec3& radii, const Vec3& p,
                                               double band) noexcept {
  // f(p) = sum p_i^2 / r_i^2 - 1 vanishes on the surface; f / |grad f| is the signed distance to
  // first order.
  const Vec3 scaled = p.cwiseQuotient(radii);
  const Vec3 gradient = 2.0 * scaled.cwiseQuotient(radii);
  const double gradient_norm = gradient.norm();
  if (gradient_norm == 0.0) return std::nullopt;  // the centre: far from the surface
  const double distance = (scaled.squaredNorm() - 1.0) / gradient_norm;
  if (std::abs(distance) > band) return std::nullopt;
  const Vec3 normal = gradient / gradient_norm;
  return PointSurface{distance, p - distance * normal, normal};
}

}  // namespace mrh::geometry::internal
