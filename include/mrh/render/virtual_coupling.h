// SPDX-License-Identifier: Apache-2.0
// The spring–damper of baseline B3 (virtual coupling, Colgate et al. 1995; SPEC §1.4 B3).
#pragma once

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

}  // namespace mrh::render
