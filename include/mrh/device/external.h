// SPDX-License-Identifier: Apache-2.0
// A device fed by the caller's own servo loop (embedding mrhaptics in an existing application).
#pragma once

#include <memory>

#include "mrh/device/device.h"

namespace mrh::device {

/// The caller writes each reading with Feed() and reads the commanded wrench back with
/// commanded(). Feed, Read, SetWrench and commanded run on the same (haptic) thread. RT-safe.
class ExternalDevice final : public Device {
 public:
  explicit ExternalDevice(const Specifications& specs = {}) : specs_(specs) {}

  const Specifications& specifications() const override { return specs_; }

  /// Stores the reading the next Read() returns. RT-safe.
  void Feed(const DeviceState& state) noexcept { state_ = state; }

  DeviceState Read(double t) noexcept override {
    DeviceState s = state_;
    s.t = t;
    return s;
  }

  void SetWrench(const Wrench& w_D) noexcept override { commanded_ = w_D; }

  /// The wrench last commanded (device frame). RT-safe.
  const Wrench& commanded() const noexcept { return commanded_; }

 private:
  Specifications specs_;
  DeviceState state_;
  Wrench commanded_;
};

}  // namespace mrh::device
