// SPDX-License-Identifier: Apache-2.0
// The haptic material of a touched geom, as it travels in the IR to the haptic thread.
#pragma once

namespace mrh::ir {

/// A contact transient's parameters (Okamura, Cutkosky & Dennerlein 2001): at contact onset
/// with normal approach speed v (m/s) the user feels Q(t) = a·v·e^(−B t)·sin(2π f t) along the
/// contact normal, t from the onset. amplitude = 0 means no transient.
struct Vibration {
  double amplitude = 0.0;  ///< a (N per m/s of approach speed, >= 0)
  double decay = 0.0;      ///< B (1/s, > 0 when amplitude > 0)
  double frequency = 0.0;  ///< f (Hz, > 0 when amplitude > 0)
};

/// The rendering gains of one touched geom. `has_material` false: the geom has no session
/// material, and the method renders it with its own `rendering.*` gains (the other fields are
/// then unused). Filled by the physics side from a per-geom table made at setup.
struct ContactMaterial {
  bool has_material = false;
  double stiffness = 0.0;  ///< N/m (k of eq. 4.11, k_t of eq. 3.7)
  double damping = 0.0;    ///< N·s/m
  double friction = 0.0;   ///< Coulomb μ (dimensionless)
  Vibration vibration;
};

/// The gains a contact is rendered with: its material's, or `rendering.*` without one.
struct ContactGains {
  double stiffness = 0.0;  ///< N/m
  double damping = 0.0;    ///< N·s/m
  double friction = 0.0;   ///< Coulomb μ
};

/// The material's gains if it has one, else `fallback` (the method's rendering.* gains).
/// RT-safe.
inline ContactGains GainsOf(const ContactMaterial& m, const ContactGains& fallback) noexcept {
  if (!m.has_material) return fallback;
  return ContactGains{m.stiffness, m.damping, m.friction};
}

}  // namespace mrh::ir
