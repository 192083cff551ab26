// SPDX-License-Identifier: Apache-2.0
// A two-finger pinch trajectory for the simulated hand: close, lift, hold, lower, open.
#pragma once

#include <vector>

#include "mrh/core/spatial.h"
#include "mrh/device/simulated.h"

namespace mrh::device {

/// The targets of two fingertips that pinch an object between them, lift it, hold it, put it
/// down and let go. Device frame, identity orientation. Times in s, lengths in m.
struct PinchSettings {
  Vec3 center = Vec3::Zero();  ///< midpoint of the fingertips at the start (m)
  Vec3 axis = Vec3::UnitY();   ///< direction from finger 0 to finger 1 (normalized on use)
  double open_width = 0.14;    ///< fingertip centres' distance before and after (m, > 0)
  /// Target distance while squeezing (m, > 0, < open_width). The hand is a spring toward it, so
  /// the fingertips stop where the contact force balances the hand's pull: narrower than the
  /// object squeezes harder.
  double grip_width = 0.09;
  double lift = 0.05;       ///< upward (+z) travel while held (m, >= 0)
  double close_time = 0.5;  ///< s from open to the grip
  double lift_time = 0.5;   ///< s from the grip to the lifted pose
  double hold_time = 1.0;   ///< s held still
  double lower_time = 0.5;  ///< s back down
  double open_time = 0.5;   ///< s from the grip back to open
  /// @throws mrh::InvalidArgument naming the field when a width or time is not finite and > 0,
  /// the grip is not narrower than open, or lift < 0.
  void Validate() const;

  /// Total length of the trajectory (s).
  double duration() const { return close_time + lift_time + hold_time + lower_time + open_time; }
};

/// The keyframes of fingertip `finger` (0 at center − axis·width/2, 1 at center + axis·width/2)
/// for device::MakeHandDevice or MakeScriptedDevice: open at 0, gripping at close_time, lifted
/// after lift_time, held for hold_time, down after lower_time, open again after open_time.
/// @throws mrh::InvalidArgument (Validate, or finger not 0 or 1).
std::vector<Keyframe> PinchKeyframes(const PinchSettings& pinch, int finger);

}  // namespace mrh::device
