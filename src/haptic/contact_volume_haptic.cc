// SPDX-License-Identifier: Apache-2.0
// Baseline B2, haptic half: the penalty wrench on the pointer goes to the device.
#include "contact_volume_haptic.h"

#include "mrh/haptic/methods.h"

namespace mrh::haptic::internal {

void ContactVolumeHaptic::Adopt(const ir::PhysicsSnapshot& snapshot) noexcept {
  wrench_ = snapshot.pointer_wrench_W;
  contacts_ = snapshot.pointer_contacts;
}

void ContactVolumeHaptic::HapticTick(const TickInput& /*in*/, TickOutput* out) noexcept {
  if (!wrench_.f.allFinite() || !wrench_.tau.allFinite()) {
    out->w_W = Wrench{};
    out->status = kContactVolumeBadInput;
    return;
  }
  out->w_W = wrench_;
  out->contacts = contacts_;
}

void ContactVolumeHaptic::EndPeriod(ir::HapticReport* report) noexcept {
  report->impulses.Clear();
}

}  // namespace mrh::haptic::internal
