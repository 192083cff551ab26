// SPDX-License-Identifier: Apache-2.0
// Merging of haptic reports (the physics side may receive several periods at once).
#include "mrh/ir/snapshot.h"

namespace mrh::ir {

void HapticReport::AddImpulse(int body, const Vec3& linear, const Vec3& angular,
                              const Vec3& force) noexcept {
  for (BodyImpulse& entry : impulses) {
    if (entry.body == body) {
      entry.linear += linear;
      entry.angular += angular;
      entry.last_force = force;
      return;
    }
  }
  if (!impulses.PushBack(BodyImpulse{body, linear, angular, force})) {
    status |= kStatusBodiesFull;
  }
}

void HapticReport::MergeLater(const HapticReport& later) noexcept {
  // The last force is the later period's: a body it did not touch had zero force at its end.
  for (BodyImpulse& entry : impulses) entry.last_force = Vec3::Zero();
  for (const BodyImpulse& entry : later.impulses) {
    AddImpulse(entry.body, entry.linear, entry.angular, entry.last_force);
  }
  for (const LocalBodyState& state : later.local_states) {
    bool replaced = false;
    for (LocalBodyState& entry : local_states) {
      if (entry.body == state.body) {
        entry = state;
        replaced = true;
      }
    }
    if (!replaced && !local_states.PushBack(state)) status |= kStatusBodiesFull;
  }
  period = later.period;
  ticks += later.ticks;
  t = later.t;
  X_WP = later.X_WP;
  V_WP = later.V_WP;
  status |= later.status;
}

}  // namespace mrh::ir
