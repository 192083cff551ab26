// SPDX-License-Identifier: Apache-2.0
// MuJoCo's soft-constraint terms and a tangent frame, shared by the local solver's contact and
// joint rows (render/local_contact_solver.h).
#pragma once

#include <algorithm>
#include <cmath>

#include "mrh/core/spatial.h"

namespace mrh::render::internal {

/// Two unit tangents completing the unit normal n to a right-handed frame.
inline void Tangents(const Vec3& n, Vec3* t1, Vec3* t2) {
  const Vec3 axis = std::abs(n.x()) < 0.9 ? Vec3::UnitX() : Vec3::UnitY();
  *t1 = n.cross(axis).normalized();
  *t2 = n.cross(*t1);
}

/// MuJoCo's impedance d(|r|) of solimp (dmin, dmax, width, midpoint, power) at violation depth.
inline double Impedance(const double* solimp, double depth) {
  const double dmin = solimp[0], dmax = solimp[1], width = solimp[2];
  const double mid = solimp[3], power = solimp[4];
  if (!(width > 0.0) || depth >= width) return std::clamp(dmax, 1e-4, 0.9999);
  const double x = std::max(0.0, depth / width);
  double y = x;
  if (power > 1.0) {
    y = x <= mid ? std::pow(x, power) / std::pow(mid, power - 1.0)
                 : 1.0 - std::pow(1.0 - x, power) / std::pow(1.0 - mid, power - 1.0);
  }
  return std::clamp(dmin + y * (dmax - dmin), 1e-4, 0.9999);
}

/// MuJoCo's reference-acceleration gains of solref for a constraint of solimp's dmax: a = −b v
/// − k imp r. A positive solref is (time constant, damping ratio), the time constant clamped to
/// two steps of dt (MuJoCo's refsafe); a negative one is (−stiffness, −damping) directly.
inline void SpringDamper(const double* solref, const double* solimp, double dt, double* k,
                         double* b) {
  const double dmax = std::clamp(solimp[1], 1e-4, 0.9999);
  if (solref[0] > 0.0) {
    const double tc = std::max(solref[0], 2.0 * dt);
    *b = 2.0 / (dmax * tc);
    *k = 1.0 / (dmax * dmax * tc * tc * solref[1] * solref[1]);
  } else {
    *k = -solref[0] / (dmax * dmax);
    *b = -solref[1] / dmax;
  }
}

/// A soft row's velocity target (m/s or rad/s) and regularisation R.
struct SoftRow {
  double target = 0.0;
  double R = 0.0;
};

/// MuJoCo's dry-friction (friction-loss) row of a coordinate moving at v0 at the tick's start:
/// its reference acceleration damps v0 (no position term); R from diag, the row's A_ii (or
/// MuJoCo's approximation of it).
inline SoftRow FrictionLossRow(const double* solref, const double* solimp, double dt, double v0,
                               double diag) {
  double k = 0.0, b = 0.0;
  SpringDamper(solref, solimp, dt, &k, &b);
  const double imp = Impedance(solimp, 0.0);
  return SoftRow{v0 - dt * b * v0, std::max(1e-15, (1.0 - imp) / imp * diag)};
}

/// A limit row at gap (m or rad; < 0: past the limit) moving at v0 along the row: hard and
/// speculative (may close within the tick) while open, MuJoCo's soft limit past it.
inline SoftRow LimitRow(const double* solref, const double* solimp, double dt, double gap,
                        double v0, double diag) {
  if (!(gap < 0.0)) return SoftRow{-gap / dt, 0.0};
  double k = 0.0, b = 0.0;
  SpringDamper(solref, solimp, dt, &k, &b);
  const double imp = Impedance(solimp, -gap);
  return SoftRow{v0 + dt * (-b * v0 - k * imp * gap), std::max(1e-15, (1.0 - imp) / imp * diag)};
}

/// One projected Gauss–Seidel update of a scalar soft row: its impulse l (N·s or N·m·s) moved
/// to satisfy v + A Δl = target − R l with 1/(A + R) = inv_w, clamped to [lo, hi].
inline double RowUpdate(double l, double v, double target, double R, double inv_w, double lo,
                        double hi) {
  return std::clamp(l + (target - v - R * l) * inv_w, lo, hi);
}

/// The row's relative velocity change (m/s or rad/s) of an impulse change dl.
inline double RowChange(double dl, double inv_w) {
  return inv_w > 0.0 ? std::abs(dl) / inv_w : 0.0;
}

}  // namespace mrh::render::internal
