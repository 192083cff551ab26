// SPDX-License-Identifier: Apache-2.0
// The spring–damper of baseline B3 (virtual coupling, Colgate et al. 1995; thesis §1.2.3, §2.2).
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <complex>

#include "mrh/core/spatial.h"

namespace mrh::render {

/// Gains of the coupling (session keys rendering.coupling_*).
struct CouplingGains {
  double k = 0.0;    ///< N/m
  double b = 0.0;    ///< N·s/m
  double k_r = 0.0;  ///< N·m/rad
  double b_r = 0.0;  ///< N·m·s/rad
};

/// The coupling wrench acting on the tool, world frame: F_c = k (x_h − x_t) + b (v_h − v_t) at the
/// tool origin, τ_c = k_r φ + b_r (ω_h − ω_t) with φ the rotation vector of q_h q_t⁻¹. Poses are
/// body-origin poses (h: the device/pointer, t: the tool), v the origins' velocities. RT-safe.
inline Wrench CouplingWrench(const Pose& X_Wh, const Twist& V_Wh, const Pose& X_Wt,
                             const Twist& V_Wt, const CouplingGains& g) noexcept {
  Wrench w;
  w.f = g.k * (X_Wh.p - X_Wt.p) + g.b * (V_Wh.v - V_Wt.v);
  const Vec3 phi = RotationVectorFromQuat(X_Wh.q * X_Wt.q.conjugate());
  w.tau = g.k_r * phi + g.b_r * (V_Wh.w - V_Wt.w);
  return w;
}

/// How fast the coupled tool's free motion grows or decays per haptic tick: the spectral radius
/// of the loop one coupling axis forms in this project's schedule, for a = k h²/m and c = b h/m
/// (h = haptic_dt; for rotation k_r, b_r and the tool's inertia about that axis).
///
/// Why this loop: the wrench rendered in tick k comes from the tool state the previous step
/// published, and it reaches the tool in the step after that (one tick late, as every
/// method's report), while MuJoCo integrates semi-implicitly. With the device held still,
/// x_{k+1} − 2x_k + x_{k−1} = −a x_{k−1} − c (x_{k−1} − x_{k−2}), whose characteristic polynomial
/// is z³ − 2z² + (1 + a + c) z − c. The loop is stable when every root has |z| < 1 (a = c = 0 gives
/// 1: the uncoupled tool drifts). Undamped coupling is never stable here (|z|² = 1 + a), and too
/// much damping is not either (c ≳ 1). RT-safe (no allocation), but meant for setup.
inline double CouplingGrowthPerTick(double a, double c) noexcept {
  using C = std::complex<double>;
  const auto p = [a, c](C z) {
    return ((z - 2.0) * z + (1.0 + a + c)) * z - c;
  };
  // Durand–Kerner iteration from the usual non-symmetric start.
  std::array<C, 3> z{C(1.0, 0.0), C(0.4, 0.9), C(0.4, 0.9) * C(0.4, 0.9)};
  for (int iteration = 0; iteration < 200; ++iteration) {
    std::array<C, 3> next = z;
    for (int i = 0; i < 3; ++i) {
      C d(1.0, 0.0);
      for (int j = 0; j < 3; ++j) {
        if (j != i) d *= z[i] - z[j];
      }
      if (std::abs(d) > 0.0) next[i] = z[i] - p(z[i]) / d;
    }
    z = next;
  }
  return std::max({std::abs(z[0]), std::abs(z[1]), std::abs(z[2])});
}

}  // namespace mrh::render
