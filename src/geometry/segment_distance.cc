// SPDX-License-Identifier: Apache-2.0
// Closest points between two segments: the exact core distance of sphere and capsule pairs.
#include "geometry/segment_distance.h"

#include <algorithm>

namespace mrh::geometry::internal {
namespace {

// Below this fraction of |d_a|^2 |d_b|^2 the segments count as parallel: the closed-form
// parameter would divide roundoff by roundoff, and any closest pair is then valid.
constexpr double kParallelTolerance = 1e-14;

double Clamp01(double x) {
  return std::clamp(x, 0.0, 1.0);
}

// Parameters (s on A, t on B) of a closest pair, given the segment directions and r = a0 - b0.
void ClosestParameters(const Vec3& d_a, const Vec3& d_b, const Vec3& r, double* s, double* t) {
  const double a = d_a.squaredNorm();
  const double e = d_b.squaredNorm();
  const double f = d_b.dot(r);
  if (a == 0.0 && e == 0.0) {
    *s = 0.0;
    *t = 0.0;
    return;
  }
  if (a == 0.0) {
    *s = 0.0;
    *t = Clamp01(f / e);
    return;
  }
  const double c = d_a.dot(r);
  if (e == 0.0) {
    *t = 0.0;
    *s = Clamp01(-c / a);
    return;
  }
  const double b = d_a.dot(d_b);
  const double denom = a * e - b * b;
  *s = denom > kParallelTolerance * a * e ? Clamp01((b * f - c * e) / denom) : 0.0;
  // The closest point on B's line to A(s); if it falls outside B, clamp and redo A.
  *t = (b * *s + f) / e;
  if (*t < 0.0) {
    *t = 0.0;
    *s = Clamp01(-c / a);
  } else if (*t > 1.0) {
    *t = 1.0;
    *s = Clamp01((b - c) / a);
  }
}

}  // namespace

SegmentClosestPoints ClosestPointsOnSegments(const Vec3& a0, const Vec3& a1, const Vec3& b0,
                                             const Vec3& b1) noexcept {
  const Vec3 d_a = a1 - a0;
  const Vec3 d_b = b1 - b0;
  double s = 0.0;
  double t = 0.0;
  ClosestParameters(d_a, d_b, a0 - b0, &s, &t);
  SegmentClosestPoints out;
  out.p_a = a0 + s * d_a;
  out.p_b = b0 + t * d_b;
  out.distance = (out.p_b - out.p_a).norm();
  return out;
}

}  // namespace mrh::geometry::internal
