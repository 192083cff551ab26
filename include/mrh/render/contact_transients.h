// SPDX-License-Identifier: Apache-2.0
// Contact transients: decaying sinusoids started at contact onset (material display).
#pragma once

#include <array>
#include <cstddef>

#include "mrh/core/spatial.h"
#include "mrh/ir/material.h"
#include "mrh/render/tick_ir.h"

namespace mrh::render {

/// Transients alive at once; a further onset is dropped (and counted) while all are busy.
inline constexpr std::size_t kMaxTransients = 16;
/// Geoms with a vibration tracked for onset per tick; beyond this a touch is not tracked.
inline constexpr std::size_t kMaxTouchedGeoms = 64;
/// A transient ends when its envelope e^(−B t) falls below this (−80 dB of its start).
inline constexpr double kTransientEndEnvelope = 1e-4;

/// The open-loop vibration of Okamura, Cutkosky & Dennerlein (2001): when the pointer starts
/// touching a geom whose material has a vibration (ir::Vibration::amplitude > 0), a transient
/// Q(t) = a·v·e^(−B t)·sin(2π f t) starts along that contact's unit normal n_W (object →
/// pointer), v the normal approach speed at onset (m/s, >= 0) and t from the onset tick (Q = 0
/// at the onset tick itself). Transients of several onsets overlap and are summed. A geom is
/// "touched" in a tick when the method reports a force-carrying contact with it (Touch); an
/// onset is a touched geom that was not touched in the previous tick.
///
/// The transient is a display effect: the method adds Force() to the wrench it renders on the
/// hand (the safety layer clamps the sum afterwards) and sends no reaction to the object.
/// Fixed capacity, no allocation: every member is RT-safe. One instance per haptic half.
class ContactTransients {
 public:
  /// Reports a force-carrying contact with `geom` this tick. At onset (the geom was not touched
  /// last tick) and with vibration.amplitude > 0, starts a transient along n_W (unit, world)
  /// with v = max(0, approach_speed). Geoms without vibration are ignored. RT-safe.
  void Touch(int geom, const Vec3& n_W, double approach_speed,
             const ir::Vibration& vibration) noexcept;

  /// Ends the tick: the sum of the live transients' forces at this tick (N, world), then
  /// advances their clocks by dt (s) and drops the finished ones. RT-safe.
  Vec3 EndTick(double dt) noexcept;

  /// Forgets every transient and touch. RT-safe.
  void Reset() noexcept;

  /// Transients alive after the last EndTick.
  std::size_t active() const noexcept { return live_; }

  /// Onsets dropped because kMaxTransients were alive.
  std::size_t dropped() const noexcept { return dropped_; }

 private:
  struct Transient {
    Vec3 n_W = Vec3::Zero();
    double peak = 0.0;   // a·v (N)
    double decay = 0.0;  // B (1/s)
    double omega = 0.0;  // 2π f (rad/s)
    double t = 0.0;      // s since onset
  };

  bool TouchedLastTick(int geom) const noexcept;

  std::array<Transient, kMaxTransients> transients_{};
  std::size_t live_ = 0;
  std::size_t dropped_ = 0;
  std::array<int, kMaxTouchedGeoms> touched_{};
  std::size_t touched_count_ = 0;
  std::array<int, kMaxTouchedGeoms> previous_{};
  std::size_t previous_count_ = 0;
};

/// Ends the tick of `transients` and adds their force to the rendered force `f_W` (N, world).
/// Adds nothing while no transient is alive, so a scene without vibration renders exactly as
/// without this layer. RT-safe.
inline void AddTransientForce(double dt, ContactTransients* transients, Vec3* f_W) noexcept {
  const bool live = transients->active() > 0;
  const Vec3 q = transients->EndTick(dt);
  if (live || transients->active() > 0) *f_W += q;
}

/// Reports to `transients` every pair of `ir` with a penetrating point, with the pair's
/// approach speed n·(v_object − v_pointer) at its plane point (pointer twist V_WP at X_WP).
/// For the methods that render the geometric IR. RT-safe.
void TouchPairs(const TickIr& ir, const Pose& X_WP, const Twist& V_WP,
                ContactTransients* transients) noexcept;

}  // namespace mrh::render
