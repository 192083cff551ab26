// SPDX-License-Identifier: Apache-2.0
// Baseline B2 `contact-volume`: the haptic half (the pointer's penalty wrench, displayed).
#pragma once

#include "mrh/haptic/method_haptic.h"

namespace mrh::haptic::internal {

/// B2, haptic half (RT-safe): the device is connected directly to the pointer, so each tick
/// displays the penalty wrench the scene exerted on the pointer in the newest 1 ms step
/// (ir::PhysicsSnapshot::pointer_wrench_W, torque about the pointer origin). It sends no
/// impulse: the physics half applies the reactions itself. A non-finite wrench displays zero
/// with kContactVolumeBadInput. Its physics half is physics::internal::ContactVolumePhysics.
class ContactVolumeHaptic final : public MethodHaptic {
 public:
  void Adopt(const ir::PhysicsSnapshot& snapshot) noexcept override;
  void HapticTick(const TickInput& in, TickOutput* out) noexcept override;
  void EndPeriod(ir::HapticReport* report) noexcept override;

 private:
  Wrench wrench_;
  int contacts_ = 0;
};

}  // namespace mrh::haptic::internal
