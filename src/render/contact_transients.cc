// SPDX-License-Identifier: Apache-2.0
// Contact transients: onset detection per geom and the sum of decaying sinusoids.
#include "mrh/render/contact_transients.h"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace mrh::render {

bool ContactTransients::TouchedLastTick(int geom) const noexcept {
  const auto end = previous_.begin() + static_cast<std::ptrdiff_t>(previous_count_);
  return std::find(previous_.begin(), end, geom) != end;
}

void ContactTransients::Touch(int geom, const Vec3& n_W, double approach_speed,
                              const ir::Vibration& vibration) noexcept {
  if (!(vibration.amplitude > 0.0)) return;
  // Several contacts of one geom in a tick are one touch.
  const auto end = touched_.begin() + static_cast<std::ptrdiff_t>(touched_count_);
  if (std::find(touched_.begin(), end, geom) != end) return;
  if (touched_count_ == kMaxTouchedGeoms) return;
  touched_[touched_count_++] = geom;
  if (TouchedLastTick(geom)) return;
  if (live_ == kMaxTransients) {
    ++dropped_;
    return;
  }
  const double v = std::isfinite(approach_speed) ? std::max(0.0, approach_speed) : 0.0;
  transients_[live_++] = Transient{n_W, vibration.amplitude * v, vibration.decay,
                                   2.0 * std::numbers::pi * vibration.frequency, 0.0};
}

Vec3 ContactTransients::EndTick(double dt) noexcept {
  Vec3 f = Vec3::Zero();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < live_; ++i) {
    Transient& q = transients_[i];
    const double envelope = std::exp(-q.decay * q.t);
    f += (q.peak * envelope * std::sin(q.omega * q.t)) * q.n_W;
    q.t += dt;
    // Finished transients are removed by moving the live ones down (order does not matter).
    if (std::exp(-q.decay * q.t) >= kTransientEndEnvelope) transients_[kept++] = q;
  }
  live_ = kept;
  previous_ = touched_;
  previous_count_ = touched_count_;
  touched_count_ = 0;
  return f;
}

void ContactTransients::Reset() noexcept {
  live_ = 0;
  touched_count_ = 0;
  previous_count_ = 0;
}

void TouchPairs(const TickIr& ir, const Pose& X_WP, const Twist& V_WP,
                ContactTransients* transients) noexcept {
  for (const TickPair& pair : ir.pairs) {
    if (!(pair.material.vibration.amplitude > 0.0)) continue;
    bool touching = false;
    for (int k = pair.first; k < pair.first + pair.count && !touching; ++k) {
      touching = ir.points[static_cast<std::size_t>(k)].depth > 0.0;
    }
    if (!touching) continue;
    const Vec3 v_object = pair.V_WCm.v + pair.V_WCm.w.cross(pair.c_W - pair.p_WCm);
    const Vec3 v_pointer = V_WP.v + V_WP.w.cross(pair.c_W - X_WP.p);
    transients->Touch(pair.object_geom, pair.n_W, pair.n_W.dot(v_object - v_pointer),
                      pair.material.vibration);
  }
}

}  // namespace mrh::render
