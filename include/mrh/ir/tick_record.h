// SPDX-License-Identifier: Apache-2.0
// One haptic tick as the haptic thread records it for the recorder (haptic → physics thread).
#pragma once

#include <cstdint>

#include "mrh/core/spatial.h"

namespace mrh::ir {

/// One haptic tick as recorded (world frame). Written by the haptic thread into a lock-free
/// ring, read by the physics thread (or the lockstep loop), which hands it to the Recorder.
struct TickRecord {
  std::int64_t tick = 0;
  /// Index of the pointer this row belongs to (engine::EngineSettings::pointers); 0 with one
  /// pointer. With several, each tick has one record per pointer, in pointer order.
  int pointer = 0;
  double t = 0.0;      ///< s
  Pose X_WP;           ///< pointer (device tool) pose
  Pose X_WQ;           ///< proxy pose; equals X_WP when the method has no proxy
  Wrench displayed_W;  ///< wrench sent to the device, after the safety layer
  Wrench rendered_W;   ///< wrench the method rendered (what the physics saw)
  int contacts = 0;
  std::uint32_t safety_bits = 0;  ///< device::SafetyBits
  /// The method's status bits this tick (TickOutput::status; their names per method are
  /// engine::Method::status_bits, e.g. "proxy.not_converged").
  std::uint32_t method_status = 0;
};

}  // namespace mrh::ir
